#include "facecap/expr/expression_mapper.hpp"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "facecap/core/error.hpp"

#ifndef FACECAP_SOURCE_DIR
#define FACECAP_SOURCE_DIR "."
#endif

namespace facecap {

namespace fs = std::filesystem;

fs::path default_expression_models_dir() {
  if (const char* v = std::getenv("FACECAP_EXPRESSION_MODELS"); v != nullptr && *v != '\0') return v;
  return fs::path(FACECAP_SOURCE_DIR) / "models" / "expressions";
}

ExpressionMapper::ExpressionMapper(fs::path models_dir) : dir_(std::move(models_dir)) {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) {
    throw Error("expression models not found: " + dir_.string() + " (set FACECAP_EXPRESSION_MODELS)");
  }
}

const EmotionPair& ExpressionMapper::pair(Emotion emotion) const {
  std::lock_guard lock(mutex_);
  auto it = pairs_.find(emotion);
  if (it != pairs_.end()) return *it->second;
  const fs::path d = dir_ / (std::string("neutral-") + to_string(emotion));
  if (!fs::is_directory(d))
    throw Error("no expression model for " + std::string(to_string(emotion)) + ": " + d.string());
  auto p = std::make_unique<EmotionPair>();
  p->g = read_mlp(d / "G.fcnn");
  p->f = read_mlp(d / "F.fcnn");
  p->d_neutral = read_mlp(d / "DX.fcnn");
  p->d_emotion = read_mlp(d / "DY.fcnn");
  std::ifstream in(d / "means.json");
  if (!in) throw Error("expression model file missing: " + (d / "means.json").string());
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto a = j.at("neutral").get<std::vector<float>>();
    const auto b = j.at("emotion").get<std::vector<float>>();
    p->mean_neutral = Eigen::Map<const Eigen::VectorXf>(a.data(), static_cast<Eigen::Index>(a.size()));
    p->mean_emotion = Eigen::Map<const Eigen::VectorXf>(b.data(), static_cast<Eigen::Index>(b.size()));
  } catch (const nlohmann::json::exception& e) {
    throw Error("bad expression model file " + (d / "means.json").string() + ": " + e.what());
  }
  const int n = p->g.inputs();
  if (p->g.outputs() != n || p->f.inputs() != n || p->f.outputs() != n || p->d_neutral.inputs() != n ||
      p->d_emotion.inputs() != n || p->d_neutral.outputs() != 1 || p->d_emotion.outputs() != 1 ||
      p->mean_neutral.size() != n || p->mean_emotion.size() != n) {
    throw Error("expression model " + d.string() + " has inconsistent sizes");
  }
  const EmotionPair& ref = *p;
  pairs_.emplace(emotion, std::move(p));
  return ref;
}

MappedWeights ExpressionMapper::map(const Eigen::VectorXf& w, Emotion from, Emotion to, MappingMethod method) const {
  if (from == to) return {w, 1.0f};
  // Any pair without neutral relays through it (§5.2.3).
  if (from != Emotion::kNeutral && to != Emotion::kNeutral) {
    return map(map(w, from, Emotion::kNeutral, method).weights, Emotion::kNeutral, to, method);
  }
  const bool forward = from == Emotion::kNeutral;
  const EmotionPair& p = pair(forward ? to : from);
  if (w.size() != p.g.inputs()) throw Error("expression weights have the wrong size for the mapping model");
  MappedWeights out;
  if (method == MappingMethod::kLinear) {
    // Eq. 5.5: y = x - mean_X + mean_Y.
    out.weights = forward ? Eigen::VectorXf(w - p.mean_neutral + p.mean_emotion)
                          : Eigen::VectorXf(w - p.mean_emotion + p.mean_neutral);
    out.weights = out.weights.cwiseMax(0.0f).cwiseMin(1.0f);
    out.confidence = 1.0f;
    return out;
  }
  out.weights = forward ? p.g.forward(w) : p.f.forward(w);
  out.confidence = (forward ? p.d_emotion : p.d_neutral).forward(out.weights)[0];
  return out;
}

}  // namespace facecap
