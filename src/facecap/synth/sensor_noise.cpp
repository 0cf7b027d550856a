#include "facecap/synth/sensor_noise.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// A uniform draw in [0, 1) as generate_canonical<float, 24> makes it from a
// 64-bit engine: one draw, rounded to a float, over 2^64.
float canonical(uint64_t draw) {
  const float u = float(draw) * 0x1p-64f;
  return u >= 1.0f ? std::nextafter(1.0f, 0.0f) : u;
}

// A point of the polar method: uniform in the unit disc, not its centre.
struct DiscPoint {
  float x, y, r2;
};

// `count` points of the disc, drawn as the polar method draws them: each try
// takes the stream's next two draws, and those outside the disc (or at its
// centre) are tried again. Draws are taken in bulk, but never more than the
// tries use, so that the stream goes on where the distribution's would.
std::vector<DiscPoint> disc_points(size_t count, std::mt19937_64& rng) {
  std::vector<DiscPoint> points(count + 1);  // one more: each try is stored, kept or not
  std::array<uint64_t, 2048> draws;          // taken a cache-sized block at a time
  size_t kept = 0;
  while (kept < count) {
    // At most two draws for each point still to come: every one is used.
    const size_t n = std::min(draws.size(), 2 * (count - kept));
    for (size_t j = 0; j < n; ++j) draws[j] = rng();
    for (size_t j = 0; j < n; j += 2) {
      DiscPoint& p = points[kept];
      p.x = 2.0f * canonical(draws[j]) - 1.0;
      p.y = 2.0f * canonical(draws[j + 1]) - 1.0;
      p.r2 = std::fma(p.x, p.x, p.y * p.y);  // as GCC fuses libstdc++'s x * x + y * y
      kept += !(p.r2 > 1.0 || p.r2 == 0.0);
    }
  }
  points.pop_back();
  return points;
}

}  // namespace

void add_sensor_noise(cv::Mat& image, double sigma, std::mt19937_64& rng) {
  CV_Assert(image.type() == CV_32FC3 && image.isContinuous());
  // Four normals a pixel: two points of the disc, each giving two.
  const size_t pixels = image.total();
  const std::vector<DiscPoint> points = disc_points(2 * pixels, rng);

  const float stddev = float(sigma / 255.0), mean = 0.0f;
  cv::Mat noise(image.size(), CV_32FC3);
  parallel_for(image.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      auto* out = noise.ptr<cv::Vec3f>(y);
      for (int x = 0; x < image.cols; ++x) {
        const size_t i = size_t(y) * image.cols + x;
        // The distribution returns y * mult first and keeps x * mult for its next call.
        float draws[4];
        for (int k = 0; k < 2; ++k) {
          const DiscPoint& p = points[2 * i + k];
          const float mult = std::sqrt(-2 * std::log(p.r2) / p.r2);
          draws[2 * k] = p.y * mult * stddev + mean;
          draws[2 * k + 1] = p.x * mult * stddev + mean;
        }
        // The colour draws in the order GCC evaluated them in the constructor
        // call Vec3f(n(rng), n(rng), n(rng)), last first.
        const float g = draws[0];
        out[x] = cv::Vec3f(std::fma(draws[3], 0.3f, g), std::fma(draws[2], 0.3f, g), std::fma(draws[1], 0.3f, g));
      }
    }
  });
  image += noise;
}

}  // namespace facecap
