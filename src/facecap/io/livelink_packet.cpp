#include "facecap/io/livelink_packet.hpp"

#include <bit>
#include <cmath>
#include <numeric>

namespace facecap {

namespace {

constexpr uint8_t kPacketVersion = 6;

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}
void put_i32(std::vector<uint8_t>& out, int32_t v) { put_u32(out, static_cast<uint32_t>(v)); }
void put_f32(std::vector<uint8_t>& out, float v) { put_u32(out, std::bit_cast<uint32_t>(v)); }
void put_string(std::vector<uint8_t>& out, std::string_view s) {
  put_i32(out, static_cast<int32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

}  // namespace

LiveLinkFrameTime LiveLinkFrameTime::at(double seconds, double fps) {
  LiveLinkFrameTime t;
  if (!(fps > 0) || !std::isfinite(fps)) fps = 30.0;
  const double ntsc = fps * 1.001;  // 23.976, 29.97, 59.94: N * 1000 / 1001
  if (std::abs(fps - std::round(fps)) < 1e-3) {
    t.rate_numerator = static_cast<int32_t>(std::lround(fps));
  } else if (std::abs(ntsc - std::round(ntsc)) < 2e-3) {
    t.rate_numerator = static_cast<int32_t>(std::lround(ntsc)) * 1000;
    t.rate_denominator = 1001;
  } else {
    const int32_t milli = static_cast<int32_t>(std::lround(fps * 1000.0));
    const int32_t g = std::gcd(milli, 1000);
    t.rate_numerator = milli / g;
    t.rate_denominator = 1000 / g;
  }
  const double frames = std::max(0.0, seconds) * t.rate_numerator / t.rate_denominator;
  t.frame = static_cast<int32_t>(std::floor(frames));
  t.sub_frame = static_cast<float>(frames - std::floor(frames));
  return t;
}

std::vector<uint8_t> livelink_packet(std::string_view device_id, std::string_view subject,
                                     const LiveLinkFrameTime& time, const LiveLinkFace::Values& values) {
  std::vector<uint8_t> out;
  out.reserve(1 + 8 + device_id.size() + subject.size() + 16 + 1 + 4 * values.size());
  out.push_back(kPacketVersion);
  put_string(out, device_id);
  put_string(out, subject);
  put_i32(out, time.frame);
  put_f32(out, time.sub_frame);
  put_i32(out, time.rate_numerator);
  put_i32(out, time.rate_denominator);
  out.push_back(static_cast<uint8_t>(values.size()));
  for (const float v : values) put_f32(out, v);
  return out;
}

}  // namespace facecap
