#include "facecap/expr/expression_transform.hpp"

#include <algorithm>

namespace facecap {

ExpressionTransformer::ExpressionTransformer(const ExpressionMapper& mapper, Eigen::MatrixXd lip_rows,
                                             TransformOptions options)
    : mapper_(mapper), lip_rows_(std::move(lip_rows)), options_(std::move(options)) {
  for (const int shape : options_.kept_shapes) {
    const bool set = std::any_of(options_.shape_targets.begin(), options_.shape_targets.end(),
                                 [&](const auto& target) { return target.first == shape; });
    if (!set) kept_.push_back(shape);
  }
}

void ExpressionTransformer::keep_shapes(Eigen::VectorXf& w, const Eigen::VectorXf& tracked) const {
  for (const int shape : kept_) w[shape] = tracked[shape];
}

Eigen::VectorXf ExpressionTransformer::map_scheduled(const Eigen::VectorXf& w, double time, float& confidence) const {
  const ScheduleState s = options_.schedule.at(time);
  auto one = [&](const ScheduleKey& key, float& c) -> Eigen::VectorXf {
    const MappedWeights m = options_.shape_targets.empty() ? mapper_.map(w, options_.from, key.target, options_.method)
                                                           : with_shapes_set(w);
    c = m.confidence;
    // --intensity scales the change from the source expression.
    return w + float(key.intensity) * (m.weights - w);
  };
  float ca = 1, cb = 1;
  const Eigen::VectorXf a = one(s.a, ca);
  if (s.b_share <= 0) {
    confidence = ca;
    return a;
  }
  const Eigen::VectorXf b = one(s.b, cb);
  confidence = float((1 - s.b_share) * ca + s.b_share * cb);
  return float(1 - s.b_share) * a + float(s.b_share) * b;
}

MappedWeights ExpressionTransformer::with_shapes_set(const Eigen::VectorXf& w) const {
  MappedWeights m{w, 1.0f};  // nothing to be unsure of: every frame's target is given
  for (const auto& [shape, weight] : options_.shape_targets) m.weights[shape] = weight;
  return m;
}

std::vector<TransformedFrame> ExpressionTransformer::push(int index, double time,
                                                          const std::optional<Eigen::VectorXf>& tracked) {
  Slot slot;
  slot.frame.index = index;
  slot.frame.time = time;
  slot.frame.valid = tracked.has_value();
  if (tracked) {
    slot.frame.tracked = *tracked;
    slot.frame.mapped = map_scheduled(*tracked, time, slot.confidence);
    keep_shapes(slot.frame.mapped, *tracked);
    slot.frame.lip_only = correct_lips(lip_rows_, slot.frame.mapped, *tracked, options_.lips);
  }
  window_.push_back(std::move(slot));
  std::vector<TransformedFrame> out;
  // A frame is ready once k frames after it have arrived.
  const int k = options_.window;
  while (static_cast<int>(window_.size()) - emitted_ > k) {
    out.push_back(complete(static_cast<size_t>(emitted_)));
    ++emitted_;
    while (emitted_ > k) {
      window_.pop_front();
      --emitted_;
    }
  }
  return out;
}

std::vector<TransformedFrame> ExpressionTransformer::finish() {
  std::vector<TransformedFrame> out;
  while (emitted_ < static_cast<int>(window_.size())) {
    out.push_back(complete(static_cast<size_t>(emitted_)));
    ++emitted_;
  }
  window_.clear();
  emitted_ = 0;
  return out;
}

TransformedFrame ExpressionTransformer::complete(size_t at) {
  TransformedFrame f = window_[at].frame;
  if (!f.valid) return f;
  // Window of 2k + 1 valid frames around this one (fewer at the ends and next to gaps).
  std::vector<Eigen::VectorXf> mapped;
  std::vector<float> confidence;
  const int k = options_.window;
  for (int j = -k; j <= k; ++j) {
    const long i = static_cast<long>(at) + j;
    if (i < 0 || i >= static_cast<long>(window_.size()) || !window_[i].frame.valid) continue;
    mapped.push_back(window_[i].frame.mapped);
    confidence.push_back(window_[i].confidence);
  }
  f.smoothed = window_mean(mapped, confidence);
  keep_shapes(f.smoothed, f.tracked);  // this frame's own, not its neighbours' mean
  f.weights = correct_lips(lip_rows_, f.smoothed, f.tracked, options_.lips);
  return f;
}

}  // namespace facecap
