#include "cyclegan.hpp"

#include <torch/torch.h>

namespace facecap {

namespace {

struct MlpNetImpl : torch::nn::Module {
  torch::nn::Linear l1{nullptr}, l2{nullptr}, l3{nullptr}, l4{nullptr};
  MlpNetImpl(int in, int hidden, int out) {
    l1 = register_module("l1", torch::nn::Linear(in, hidden));
    l2 = register_module("l2", torch::nn::Linear(hidden, hidden));
    l3 = register_module("l3", torch::nn::Linear(hidden, hidden));
    l4 = register_module("l4", torch::nn::Linear(hidden, out));
    for (auto& p : parameters()) {
      torch::NoGradGuard guard;
      if (p.dim() == 2) {
        p.normal_(0.0, 0.01);  // N(0, 0.01) as §5.2.2
      } else {
        p.zero_();
      }
    }
  }
  torch::Tensor forward(torch::Tensor x) {
    x = torch::relu(l1->forward(x));
    x = torch::relu(l2->forward(x));
    x = torch::relu(l3->forward(x));
    return torch::sigmoid(l4->forward(x));
  }
};
TORCH_MODULE(MlpNet);

Mlp export_net(MlpNet& net) {
  std::vector<DenseLayer> layers;
  int index = 0;
  for (torch::nn::Linear* l : {&net->l1, &net->l2, &net->l3, &net->l4}) {
    const torch::Tensor w = (*l)->weight.detach().contiguous().to(torch::kFloat32);
    const torch::Tensor b = (*l)->bias.detach().contiguous().to(torch::kFloat32);
    DenseLayer d;
    d.weights = Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        w.data_ptr<float>(), w.size(0), w.size(1));
    d.bias = Eigen::Map<const Eigen::VectorXf>(b.data_ptr<float>(), b.size(0));
    d.activation = index++ < 3 ? Activation::kRelu : Activation::kSigmoid;
    layers.push_back(std::move(d));
  }
  return Mlp(std::move(layers));
}

torch::Tensor to_tensor(const std::vector<Eigen::VectorXf>& v) {
  const int n = static_cast<int>(v.size()), d = static_cast<int>(v.front().size());
  torch::Tensor t = torch::empty({n, d}, torch::kFloat32);
  for (int i = 0; i < n; ++i) std::memcpy(t[i].data_ptr<float>(), v[i].data(), sizeof(float) * d);
  return t;
}

}  // namespace

CycleGanModels train_cyclegan(const std::vector<Eigen::VectorXf>& xs, const std::vector<Eigen::VectorXf>& ys,
                              const CycleGanOptions& o, const TrainProgress& progress) {
  torch::manual_seed(o.seed);
  torch::set_num_threads(2);
  const int d = static_cast<int>(xs.front().size());
  const torch::Tensor x_all = to_tensor(xs), y_all = to_tensor(ys);
  MlpNet g(d, o.hidden, d), f(d, o.hidden, d), dx(d, o.hidden, 1), dy(d, o.hidden, 1);
  std::vector<torch::Tensor> gen_params = g->parameters();
  for (auto& p : f->parameters()) gen_params.push_back(p);
  std::vector<torch::Tensor> disc_params = dx->parameters();
  for (auto& p : dy->parameters()) disc_params.push_back(p);
  const auto adam = torch::optim::AdamOptions(o.learning_rate).betas({o.beta1, 0.999});
  torch::optim::Adam opt_g(gen_params, adam), opt_d(disc_params, adam);
  auto bce = [](const torch::Tensor& p, float target) {
    return torch::binary_cross_entropy(p, torch::full_like(p, target));
  };
  CycleGanModels out;
  for (int it = 0; it < o.iterations; ++it) {
    const torch::Tensor x = x_all.index_select(0, torch::randint(x_all.size(0), {o.batch_size}, torch::kLong));
    const torch::Tensor y = y_all.index_select(0, torch::randint(y_all.size(0), {o.batch_size}, torch::kLong));
    // Generators: fool the discriminators, and come back (eq. 5.1-5.3).
    opt_g.zero_grad();
    const torch::Tensor fake_y = g->forward(x), fake_x = f->forward(y);
    const torch::Tensor gan = bce(dy->forward(fake_y), 1.0f) + bce(dx->forward(fake_x), 1.0f);
    const torch::Tensor cycle = torch::l1_loss(f->forward(fake_y), x) + torch::l1_loss(g->forward(fake_x), y);
    const torch::Tensor loss_g = gan + o.cycle_weight * cycle;
    loss_g.backward();
    opt_g.step();
    // Discriminators: real against generated.
    opt_d.zero_grad();
    const torch::Tensor loss_d = bce(dy->forward(y), 1.0f) + bce(dy->forward(fake_y.detach()), 0.0f) +
                                 bce(dx->forward(x), 1.0f) + bce(dx->forward(fake_x.detach()), 0.0f);
    loss_d.backward();
    opt_d.step();
    out.final_cycle_loss = cycle.item<double>();
    if (progress && (it % 200 == 0 || it + 1 == o.iterations))
      progress(it, loss_g.item<double>(), loss_d.item<double>());
  }
  out.g = export_net(g);
  out.f = export_net(f);
  out.d_x = export_net(dx);
  out.d_y = export_net(dy);
  return out;
}

}  // namespace facecap
