#pragma once
// Datagrams to one host and port (IPv4 or IPv6), for live streams such as
// Live Link Face's (livelink_packet.hpp). UDP does not say whether anything
// listens: a send fails only where the datagram cannot leave this machine.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace facecap {

struct NetworkTarget {
  std::string host;
  int port = 0;
};

// "HOST", "HOST:PORT" or "[IPv6]:PORT" (the port `default_port` where none
// is given); throws facecap::Error, led by `what` where it is not empty,
// where the text is neither.
NetworkTarget parse_network_target(std::string_view text, int default_port, const std::string& what);

class UdpSender {
 public:
  // Throws facecap::Error where the host cannot be resolved or no socket opens.
  explicit UdpSender(const NetworkTarget& target);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  // False where the datagram could not be sent (errno's reason in last_error()).
  bool send(const std::vector<uint8_t>& datagram);
  const std::string& last_error() const { return last_error_; }
  // The address it sends to, as resolved ("127.0.0.1:11111").
  const std::string& address() const { return address_; }

 private:
  int fd_ = -1;
  std::vector<uint8_t> to_;  // the resolved sockaddr
  std::string address_;
  std::string last_error_;
};

}  // namespace facecap
