#include "facecap/pipeline/livelink_streamer.hpp"

#include <ctime>
#include <thread>

#include "facecap/io/livelink_packet.hpp"

namespace facecap {

namespace {

// Seconds since local midnight, now: the timecode the app stamps its frames with.
double time_of_day() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  std::tm local{};
  localtime_r(&t, &local);
  const auto since = now.time_since_epoch();
  const double fraction =
      std::chrono::duration<double>(since - std::chrono::floor<std::chrono::seconds>(since)).count();
  return local.tm_hour * 3600.0 + local.tm_min * 60.0 + local.tm_sec + fraction;
}

}  // namespace

LiveLinkStreamer::LiveLinkStreamer(const NetworkTarget& target, std::string subject, double fps, bool paced)
    : udp_(target), subject_(std::move(subject)), fps_(fps > 0 ? fps : 30.0), paced_(paced) {}

void LiveLinkStreamer::send(double seconds, const LiveLinkFace::Values& values) {
  if (paced_) {
    const auto now = std::chrono::steady_clock::now();
    if (!start_) start_.emplace(now, seconds);
    const auto due = start_->first + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                         std::chrono::duration<double>(seconds - start_->second));
    if (due > now) std::this_thread::sleep_until(due);
  }
  const std::vector<uint8_t> packet =
      livelink_packet("facecap", subject_, LiveLinkFrameTime::at(time_of_day(), fps_), values);
  if (udp_.send(packet)) {
    ++sent_;
  } else if (first_error_.empty()) {
    first_error_ = udp_.last_error();
  }
}

}  // namespace facecap
