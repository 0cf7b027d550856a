#pragma once
// `track --livelink-udp HOST[:PORT]`: each frame's Live Link Face values sent
// as the app's datagram (io/livelink_packet.hpp) as the frame is written, so
// that Unreal's Live Link (a MetaHuman) or any reader of that stream follows
// the capture live. A file's frames go at the file's own pace; the packets
// carry the time of day as their timecode, as the app's do.
#include <chrono>
#include <optional>
#include <string>

#include "facecap/io/livelink_face.hpp"
#include "facecap/io/udp_sender.hpp"

namespace facecap {

class LiveLinkStreamer {
 public:
  // Throws facecap::Error where the host cannot be resolved. `fps`: the
  // input's (the packets' rate); `paced`: wait for each frame's time.
  LiveLinkStreamer(const NetworkTarget& target, std::string subject, double fps, bool paced);

  // One frame at `seconds` on the input's timeline. A datagram that cannot
  // leave is counted, not fatal (the capture's files matter more).
  void send(double seconds, const LiveLinkFace::Values& values);

  int sent() const { return sent_; }
  const std::string& address() const { return udp_.address(); }
  const std::string& first_error() const { return first_error_; }

 private:
  UdpSender udp_;
  std::string subject_;
  double fps_;
  bool paced_;
  std::optional<std::pair<std::chrono::steady_clock::time_point, double>> start_;  // wall and input time of the first
  int sent_ = 0;
  std::string first_error_;
};

}  // namespace facecap
