#pragma once
// Expression mapping in blendshape-weight space (§5.2): for each emotion, the
// CycleGAN generators G (neutral -> emotion) and F (emotion -> neutral) and
// the discriminators D_X (neutral) and D_Y (emotion), loaded from
// `<models>/neutral-<emotion>/{G,F,DX,DY}.fcnn` with the domains' mean
// weights (`means.json`) for the linear baseline of eq. 5.5. Pairs without
// neutral relay through it (§5.2.3).
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "facecap/expr/emotions.hpp"
#include "facecap/expr/mlp.hpp"

namespace facecap {

// FACECAP_EXPRESSION_MODELS, else models/expressions in the source tree.
std::filesystem::path default_expression_models_dir();

struct EmotionPair {
  Mlp g, f, d_neutral, d_emotion;
  Eigen::VectorXf mean_neutral, mean_emotion;
};

struct MappedWeights {
  Eigen::VectorXf weights;
  float confidence = 1.0f;  // the target domain's discriminator on the result (eq. 5.4's c_j)
};

enum class MappingMethod { kCycleGan, kLinear };

class ExpressionMapper {
 public:
  // Throws facecap::Error naming the folder or file when models are missing or bad.
  explicit ExpressionMapper(std::filesystem::path models_dir = default_expression_models_dir());

  MappedWeights map(const Eigen::VectorXf& weights, Emotion from, Emotion to,
                    MappingMethod method = MappingMethod::kCycleGan) const;
  // Loads (and checks) the pair now; map() loads lazily otherwise.
  const EmotionPair& pair(Emotion emotion) const;

 private:
  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  mutable std::map<Emotion, std::unique_ptr<EmotionPair>> pairs_;
};

}  // namespace facecap
