#include "facecap/io/udp_sender.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

#include "facecap/core/error.hpp"

namespace facecap {

NetworkTarget parse_network_target(std::string_view text, int default_port, const std::string& what) {
  const std::string named = what.empty() ? "" : what + ": ";
  NetworkTarget t;
  t.port = default_port;
  std::string_view port;
  if (text.starts_with('[')) {  // [IPv6]:PORT
    const size_t close = text.find(']');
    if (close == std::string_view::npos)
      throw Error(named + "no ']' after the IPv6 address in '" + std::string(text) + "'");
    t.host = std::string(text.substr(1, close - 1));
    const std::string_view rest = text.substr(close + 1);
    if (!rest.empty()) {
      if (!rest.starts_with(':')) throw Error(named + "expected ':PORT' after ']' in '" + std::string(text) + "'");
      port = rest.substr(1);
    }
  } else if (const size_t colon = text.rfind(':');
             colon != std::string_view::npos && text.find(':') == colon) {  // one colon: HOST:PORT
    t.host = std::string(text.substr(0, colon));
    port = text.substr(colon + 1);
  } else {
    t.host = std::string(text);  // a name, an IPv4 address, or a bare IPv6 one
  }
  if (t.host.empty()) throw Error(named + "no host in '" + std::string(text) + "' (HOST or HOST:PORT)");
  if (port.data() != nullptr) {
    int p = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), p);
    if (port.empty() || ec != std::errc() || end != port.data() + port.size() || p < 1 || p > 65535)
      throw Error(named + "the port must be a number from 1 to 65535, not '" + std::string(port) + "'");
    t.port = p;
  }
  return t;
}

UdpSender::UdpSender(const NetworkTarget& target) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(target.port);
  if (const int rc = getaddrinfo(target.host.c_str(), port.c_str(), &hints, &found); rc != 0 || found == nullptr)
    throw Error("cannot resolve the host " + target.host + ": " + gai_strerror(rc));
  const auto* first = found->ai_addr;
  to_.assign(reinterpret_cast<const uint8_t*>(first), reinterpret_cast<const uint8_t*>(first) + found->ai_addrlen);
  const int family = found->ai_family;
  char host[INET6_ADDRSTRLEN] = "?";
  if (family == AF_INET)
    inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(first)->sin_addr, host, sizeof(host));
  else if (family == AF_INET6)
    inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6*>(first)->sin6_addr, host, sizeof(host));
  freeaddrinfo(found);
  address_ = (family == AF_INET6 ? "[" + std::string(host) + "]" : std::string(host)) + ":" + port;
  fd_ = socket(family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw Error("cannot open a UDP socket: " + std::string(std::strerror(errno)));
}

UdpSender::~UdpSender() {
  if (fd_ >= 0) close(fd_);
}

bool UdpSender::send(const std::vector<uint8_t>& datagram) {
  // Not connected: a receiver that is not (yet) listening must not turn the
  // next sends into errors (a connected UDP socket reports ICMP refusals).
  const ssize_t sent = sendto(fd_, datagram.data(), datagram.size(), MSG_NOSIGNAL,
                              reinterpret_cast<const sockaddr*>(to_.data()), static_cast<socklen_t>(to_.size()));
  if (sent == static_cast<ssize_t>(datagram.size())) return true;
  last_error_ = sent < 0 ? std::strerror(errno) : "sent in part";
  return false;
}

}  // namespace facecap
