#pragma once
// CycleGAN on blendshape-weight vectors (§5.2): generators G: X -> Y and
// F: Y -> X (53 -> 3 x 100 ReLU -> 53 sigmoid), discriminators D_X, D_Y
// (53 -> 3 x 100 ReLU -> 1 sigmoid), energy E_gan(G, D_Y) + E_gan(F, D_X) +
// lambda E_cyc (eq. 5.1-5.3, lambda = 10), Adam (learning rate 2e-4, beta1
// 0.5), weights initialised from N(0, 0.01). Trained with LibTorch; exported
// to the runtime's Eigen format (expr/mlp.hpp).
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "facecap/expr/mlp.hpp"

namespace facecap {

struct CycleGanOptions {
  int iterations = 4000;
  int batch_size = 64;  // the paper trains with batches of 1 for 200 epochs; batches of 64 take minutes
  double learning_rate = 2e-4;
  double beta1 = 0.5;
  double cycle_weight = 10.0;  // lambda
  int hidden = 100;
  uint64_t seed = 1;
};

struct CycleGanModels {
  Mlp g, f, d_x, d_y;
  double final_cycle_loss = 0;
};

using TrainProgress = std::function<void(int iteration, double generator_loss, double discriminator_loss)>;

CycleGanModels train_cyclegan(const std::vector<Eigen::VectorXf>& x, const std::vector<Eigen::VectorXf>& y,
                              const CycleGanOptions& options, const TrainProgress& progress = {});

}  // namespace facecap
