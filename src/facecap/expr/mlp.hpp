#pragma once
// A small fully connected network evaluated with Eigen: the expression
// mappings' generators (53 -> 3 x 100 ReLU -> 53 sigmoid) and discriminators
// (-> 1 sigmoid) of §5.2.2. The runtime needs no LibTorch: the trainer
// exports weights in this file format.
//
// File format (little-endian): magic "FCNN", uint32 version (1), uint32
// layer count, then per layer: uint32 inputs, uint32 outputs, uint32
// activation (0 linear, 1 ReLU, 2 sigmoid), float32 weights (outputs x
// inputs, row-major), float32 biases (outputs).
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace facecap {

enum class Activation : uint32_t { kLinear = 0, kRelu = 1, kSigmoid = 2 };

struct DenseLayer {
  Eigen::MatrixXf weights;  // outputs x inputs
  Eigen::VectorXf bias;
  Activation activation = Activation::kLinear;
};

class Mlp {
 public:
  Mlp() = default;
  explicit Mlp(std::vector<DenseLayer> layers);

  int inputs() const { return layers_.empty() ? 0 : static_cast<int>(layers_.front().weights.cols()); }
  int outputs() const { return layers_.empty() ? 0 : static_cast<int>(layers_.back().weights.rows()); }
  Eigen::VectorXf forward(const Eigen::VectorXf& x) const;
  const std::vector<DenseLayer>& layers() const { return layers_; }

 private:
  std::vector<DenseLayer> layers_;
};

// Throws facecap::Error naming the file when it is missing, truncated, of
// another version, inconsistent in its layer sizes, or holds a non-finite value.
Mlp read_mlp(const std::filesystem::path& path);
void write_mlp(const std::filesystem::path& path, const Mlp& mlp);

}  // namespace facecap
