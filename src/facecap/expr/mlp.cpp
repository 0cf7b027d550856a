#include "facecap/expr/mlp.hpp"

#include <cstring>
#include <fstream>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {
constexpr char kMagic[4] = {'F', 'C', 'N', 'N'};
constexpr uint32_t kVersion = 1;
}  // namespace

Mlp::Mlp(std::vector<DenseLayer> layers) : layers_(std::move(layers)) {
  for (size_t l = 1; l < layers_.size(); ++l) {
    if (layers_[l].weights.cols() != layers_[l - 1].weights.rows()) throw Error("network layers do not chain");
  }
}

Eigen::VectorXf Mlp::forward(const Eigen::VectorXf& x) const {
  Eigen::VectorXf a = x;
  for (const DenseLayer& layer : layers_) {
    Eigen::VectorXf z = layer.weights * a + layer.bias;
    switch (layer.activation) {
      case Activation::kRelu:
        z = z.cwiseMax(0.0f);
        break;
      case Activation::kSigmoid:
        z = (1.0f / (1.0f + (-z.array()).exp())).matrix();
        break;
      case Activation::kLinear:
        break;
    }
    a = std::move(z);
  }
  return a;
}

Mlp read_mlp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("expression model not found: " + path.string());
  auto fail = [&](const std::string& why) -> Error {
    return Error("bad expression model " + path.string() + ": " + why);
  };
  auto read_u32 = [&]() {
    uint32_t v = 0;
    if (!in.read(reinterpret_cast<char*>(&v), sizeof(v))) throw fail("truncated");
    return v;
  };
  char magic[4];
  if (!in.read(magic, 4) || std::memcmp(magic, kMagic, 4) != 0) throw fail("not a facecap network file");
  if (read_u32() != kVersion) throw fail("unsupported version");
  const uint32_t count = read_u32();
  if (count == 0 || count > 16) throw fail("impossible layer count");
  std::vector<DenseLayer> layers(count);
  for (DenseLayer& layer : layers) {
    const uint32_t inputs = read_u32(), outputs = read_u32(), activation = read_u32();
    if (inputs == 0 || outputs == 0 || inputs > 4096 || outputs > 4096 || activation > 2)
      throw fail("impossible layer");
    layer.activation = static_cast<Activation>(activation);
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w(outputs, inputs);
    layer.bias.resize(outputs);
    if (!in.read(reinterpret_cast<char*>(w.data()), std::streamsize(sizeof(float) * w.size())) ||
        !in.read(reinterpret_cast<char*>(layer.bias.data()), std::streamsize(sizeof(float) * outputs))) {
      throw fail("truncated");
    }
    if (!w.allFinite() || !layer.bias.allFinite()) throw fail("non-finite weight");
    layer.weights = w;
  }
  in.peek();
  if (!in.eof()) throw fail("trailing bytes");
  try {
    return Mlp(std::move(layers));
  } catch (const Error&) {
    throw fail("layer sizes do not chain");
  }
}

void write_mlp(const std::filesystem::path& path, const Mlp& mlp) {
  write_file(path, [&](std::ostream& out) {
    out.write(kMagic, 4);
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), sizeof(v)); };
    u32(kVersion);
    u32(static_cast<uint32_t>(mlp.layers().size()));
    for (const DenseLayer& layer : mlp.layers()) {
      u32(static_cast<uint32_t>(layer.weights.cols()));
      u32(static_cast<uint32_t>(layer.weights.rows()));
      u32(static_cast<uint32_t>(layer.activation));
      const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w = layer.weights;
      out.write(reinterpret_cast<const char*>(w.data()), std::streamsize(sizeof(float) * w.size()));
      out.write(reinterpret_cast<const char*>(layer.bias.data()), std::streamsize(sizeof(float) * layer.bias.size()));
    }
  });
}

}  // namespace facecap
