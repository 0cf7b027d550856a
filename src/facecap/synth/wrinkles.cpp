#include "facecap/synth/wrinkles.hpp"

#include <algorithm>
#include <cmath>

namespace facecap {

namespace {

constexpr float kPi = 3.14159265f;

float smooth_window(float x, float lo, float hi) {
  if (x <= lo || x >= hi) return 0.0f;
  const float s = std::sin(kPi * (x - lo) / (hi - lo));
  return s * s;
}

float distance_to_segment(const Vec2f& p, const Vec2f& a, const Vec2f& b) {
  const Vec2f ab = b - a;
  const float t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0f, 1.0f);
  return (p - (a + t * ab)).norm();
}

}  // namespace

float wrinkle_displacement(const Vec3f& q) {
  const float x = q.x(), y = q.y(), z = q.z();
  const float ax = std::abs(x);
  float d = 0.0f;
  // Forehead furrows: horizontal ridges above the brows.
  d += 0.045f * std::sin(2 * kPi * (y - 7.0f) / 0.95f) * smooth_window(y, 7.0f, 10.2f) * smooth_window(x, -5.5f, 5.5f);
  if (z > 6.0f) {
    // Nasolabial folds from the nose wings to beside the mouth corners.
    const float fold = distance_to_segment({ax, y}, {2.0f, -0.4f}, {3.3f, -4.3f});
    d -= 0.08f * std::exp(-(fold * fold) / (0.22f * 0.22f));
    // Vertical frown lines between the brows.
    d -= 0.05f * std::exp(-std::pow((ax - 0.55f) / 0.12f, 2.0f)) * smooth_window(y, 5.0f, 7.2f);
  }
  // Crow's feet: radial ripples at the outer eye corners.
  const Vec2f eye(5.3f, 3.3f);
  const Vec2f r = Vec2f(ax, y) - eye;
  const float rho = r.norm();
  if (rho < 1.8f && ax > 4.6f) {
    const float theta = std::atan2(r.y(), r.x());
    d += 0.03f * std::cos(9.0f * theta) * smooth_window(rho, 0.3f, 1.8f);
  }
  return d;
}

}  // namespace facecap
