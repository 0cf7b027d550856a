#include "facecap/expr/mlp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

Mlp small_net() {
  DenseLayer hidden;
  hidden.weights.resize(2, 3);
  hidden.weights << 1, -1, 0.5f, -2, 0, 1;
  hidden.bias = Eigen::Vector2f(0.1f, -0.2f);
  hidden.activation = Activation::kRelu;
  DenseLayer out;
  out.weights.resize(1, 2);
  out.weights << 0.5f, -0.25f;
  out.bias = Eigen::VectorXf::Constant(1, 0.3f);
  out.activation = Activation::kSigmoid;
  return Mlp({hidden, out});
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void write_bytes(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

void expect_error_naming(const fs::path& p, const std::string& what) {
  try {
    read_mlp(p);
    FAIL() << "no error for " << what;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(p.filename().string()), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Mlp, ForwardMatchesHandComputation) {
  const Eigen::VectorXf x = Eigen::Vector3f(1, 2, 4);
  // hidden: relu(1 - 2 + 2 + 0.1) = 1.1, relu(-2 + 0 + 4 - 0.2) = 1.8
  const float z = 0.5f * 1.1f - 0.25f * 1.8f + 0.3f;
  const Eigen::VectorXf y = small_net().forward(x);
  ASSERT_EQ(y.size(), 1);
  EXPECT_NEAR(y[0], 1.0f / (1.0f + std::exp(-z)), 1e-6f);
}

TEST(Mlp, RejectsInconsistentLayers) {
  DenseLayer a;
  a.weights = Eigen::MatrixXf::Zero(4, 3);
  a.bias = Eigen::VectorXf::Zero(4);
  DenseLayer b;
  b.weights = Eigen::MatrixXf::Zero(2, 5);  // expects 5 inputs, gets 4
  b.bias = Eigen::VectorXf::Zero(2);
  EXPECT_THROW(Mlp({a, b}), Error);
}

TEST(Mlp, WriteReadRoundTripIsExact) {
  TempDir dir;
  const Mlp net = small_net();
  write_mlp(dir.path() / "net.fcnn", net);
  const Mlp back = read_mlp(dir.path() / "net.fcnn");
  ASSERT_EQ(back.layers().size(), 2u);
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(back.layers()[l].weights, net.layers()[l].weights);
    EXPECT_EQ(back.layers()[l].bias, net.layers()[l].bias);
    EXPECT_EQ(back.layers()[l].activation, net.layers()[l].activation);
  }
}

TEST(Mlp, BadFilesAreClearErrors) {
  TempDir dir;
  const fs::path good = dir.path() / "net.fcnn";
  write_mlp(good, small_net());
  const std::string bytes = read_bytes(good);

  expect_error_naming(dir.path() / "missing.fcnn", "a missing file");

  write_bytes(dir.path() / "truncated.fcnn", bytes.substr(0, bytes.size() - 5));
  expect_error_naming(dir.path() / "truncated.fcnn", "a truncated file");

  std::string magic = bytes;
  magic[0] = 'X';
  write_bytes(dir.path() / "magic.fcnn", magic);
  expect_error_naming(dir.path() / "magic.fcnn", "a wrong magic");

  // The first weight (after magic, version, count, inputs, outputs, activation) as NaN.
  std::string nan = bytes;
  const float q = std::nanf("");
  std::memcpy(nan.data() + 4 + 4 * 5, &q, sizeof q);
  write_bytes(dir.path() / "nan.fcnn", nan);
  expect_error_naming(dir.path() / "nan.fcnn", "a NaN weight");
}

}  // namespace facecap
