#pragma once
// The other end of a Live Link Face stream, for tests: a UDP socket on an
// ephemeral loopback port, and a decoder of the app's version-6 datagram
// written from its layout (network byte order: u8 version, i32 length +
// device id, i32 length + subject, i32 frame, f32 sub-frame, i32 rate
// numerator, i32 rate denominator, u8 count, count x f32), apart from the
// encoder it checks.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace facecap::test {

struct LiveLinkDatagram {
  int version = 0;
  std::string device_id, subject;
  int32_t frame = 0;
  float sub_frame = 0;
  int32_t rate_numerator = 0, rate_denominator = 0;
  std::vector<float> values;
};

inline LiveLinkDatagram decode_livelink(const std::vector<uint8_t>& d) {
  size_t at = 0;
  auto take = [&](size_t n) {
    if (at + n > d.size()) throw std::runtime_error("datagram too short");
    const size_t from = at;
    at += n;
    return from;
  };
  auto u32 = [&] {
    const size_t i = take(4);
    return uint32_t(d[i]) << 24 | uint32_t(d[i + 1]) << 16 | uint32_t(d[i + 2]) << 8 | uint32_t(d[i + 3]);
  };
  auto text = [&] {
    const uint32_t n = u32();
    const size_t i = take(n);
    return std::string(d.begin() + i, d.begin() + i + n);
  };
  LiveLinkDatagram p;
  p.version = d.at(take(1));
  p.device_id = text();
  p.subject = text();
  p.frame = int32_t(u32());
  p.sub_frame = std::bit_cast<float>(u32());
  p.rate_numerator = int32_t(u32());
  p.rate_denominator = int32_t(u32());
  const int count = d.at(take(1));
  for (int k = 0; k < count; ++k) p.values.push_back(std::bit_cast<float>(u32()));
  if (at != d.size()) throw std::runtime_error("datagram too long");
  return p;
}

class UdpReceiver {
 public:
  UdpReceiver() {
    fd_ = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    socklen_t len = sizeof(a);
    if (fd_ < 0 || bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 ||
        getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
      throw std::runtime_error("cannot open a loopback UDP socket");
    port_ = ntohs(a.sin_port);
    // A large buffer: a test reads the datagrams after the run sent them all.
    const int size = 8 << 20;
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size));
  }
  ~UdpReceiver() {
    if (fd_ >= 0) close(fd_);
  }
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  int port() const { return port_; }

  // The next datagram, or nothing within `timeout_ms`.
  std::optional<std::vector<uint8_t>> receive(int timeout_ms = 2000) const {
    timeval tv{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    std::vector<uint8_t> buffer(65536);
    const ssize_t n = recv(fd_, buffer.data(), buffer.size(), 0);
    if (n < 0) return std::nullopt;
    buffer.resize(size_t(n));
    return buffer;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace facecap::test
