#include "facecap/swap/chroma_spread.hpp"

#include <algorithm>
#include <array>

#include "facecap/core/statistics.hpp"

namespace facecap {

namespace {

constexpr int kMinVertices = 50;
constexpr float kLow = 0.10f, kHigh = 0.90f;

}  // namespace

ChromaSpread::ChromaSpread(const Positions& source, const Positions& target, const std::vector<bool>& use) {
  std::array<std::vector<float>, 2> s, t;
  for (int v = 0; v < static_cast<int>(source.cols()); ++v) {
    if (!use[v]) continue;
    for (int k = 0; k < 2; ++k) {
      s[k].push_back(source(k + 1, v));
      t[k].push_back(target(k + 1, v));
    }
  }
  if (static_cast<int>(s[0].size()) < kMinVertices) return;
  for (int k = 0; k < 2; ++k) {
    const float source_spread = quantile(s[k], kHigh) - quantile(s[k], kLow);
    const float target_spread = quantile(t[k], kHigh) - quantile(t[k], kLow);
    centre_[k] = quantile(s[k], 0.5f);
    if (source_spread > 1e-6f) scale_[k] = std::clamp(target_spread / source_spread, 0.0f, 1.0f);
  }
}

Vec3f ChromaSpread::narrow(const Vec3f& yc) const {
  Vec3f out = yc;
  for (int k = 0; k < 2; ++k) out[k + 1] = centre_[k] + scale_[k] * (yc[k + 1] - centre_[k]);
  return out;
}

Positions ChromaSpread::narrow(const Positions& yc) const {
  Positions out(3, yc.cols());
  for (int v = 0; v < static_cast<int>(yc.cols()); ++v) out.col(v) = narrow(Vec3f(yc.col(v)));
  return out;
}

}  // namespace facecap
