// Sending a URScript program to a UR controller's secondary interface (script_sender.hpp).

#include "script_sender.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "comply/hardware/backend.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/hardware/tcp_connect.hpp"

namespace comply::ur {

namespace {

/// A controller greets a client of its secondary interface with its version message (79 bytes
/// and more) and may drop a program sent before that was read: it is read first, for up to
/// 0.2 s (an emulator may send none).
void skipGreeting(int socket) {
  constexpr std::size_t kGreetingBytes = 79;
  const double until_s = hardware::monotonicSeconds() + 0.2;
  std::array<char, 4096> buffer{};
  for (std::size_t read = 0; read < kGreetingBytes;) {
    const double left_s = until_s - hardware::monotonicSeconds();
    pollfd readable{socket, POLLIN, 0};
    if (left_s <= 0.0 || ::poll(&readable, 1, static_cast<int>(std::ceil(left_s * 1e3))) <= 0) {
      return;
    }
    const ssize_t n = ::recv(socket, buffer.data(), buffer.size(), 0);
    if (n <= 0) {
      return;
    }
    read += static_cast<std::size_t>(n);
  }
}

}  // namespace

void sendScript(const std::string& host, std::uint16_t port, const std::string& script,
                double timeout_s) {
  const std::string where = host + ":" + std::to_string(port);
  std::string why;
  const int socket = hardware::connectTcp(host, port, timeout_s, why);
  timeval limit{};
  limit.tv_sec = static_cast<time_t>(timeout_s);
  limit.tv_usec = static_cast<suseconds_t>((timeout_s - std::floor(timeout_s)) * 1e6);
  ::setsockopt(socket, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
  bool sent = socket >= 0;
  if (sent) {
    skipGreeting(socket);
  }
  for (std::size_t at = 0; sent && at < script.size();) {
    const ssize_t n = ::send(socket, script.data() + at, script.size() - at, MSG_NOSIGNAL);
    sent = n > 0;
    at += sent ? static_cast<std::size_t>(n) : 0;
  }
  if (socket >= 0 && !sent) {
    why = std::strerror(errno);
  }
  if (socket >= 0) {
    ::shutdown(socket, SHUT_WR);
    ::close(socket);
  }
  if (!sent) {
    throw hardware::BackendError("UR: cannot send the control program to " + where +
                                 " (the secondary interface): " + why);
  }
}

}  // namespace comply::ur
