// A TCP port serving one text connection at a time (text_port.hpp).

#include "text_port.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "comply/hardware/loop_clock.hpp"

namespace comply::ur {
namespace {

constexpr int kPollMs = 50;  // how soon a stop is noticed

bool readable(int socket, int timeout_ms) {
  pollfd entry{socket, POLLIN, 0};
  return ::poll(&entry, 1, timeout_ms) > 0;
}

}  // namespace

bool TextConnection::fill(int timeout_ms) {
  if (closed_ || stopping_.load(std::memory_order_relaxed) || !readable(socket_, timeout_ms)) {
    return !closed_ && !stopping_.load(std::memory_order_relaxed);
  }
  char chunk[4096];
  const ssize_t n = ::recv(socket_, chunk, sizeof chunk, 0);
  if (n <= 0) {
    closed_ = true;
    return false;
  }
  buffer_.append(chunk, static_cast<std::size_t>(n));
  return true;
}

bool TextConnection::readLine(std::string& line) {
  for (;;) {
    const std::size_t end = buffer_.find('\n');
    if (end != std::string::npos) {
      line = buffer_.substr(0, end);
      buffer_.erase(0, end + 1);
      if (!line.empty() && line.back() == '\r') {
        line.pop_back();
      }
      return true;
    }
    if (!fill(kPollMs)) {
      return false;
    }
  }
}

std::string TextConnection::readAll(double idle_s) {
  double last_byte_s = hardware::monotonicSeconds();
  // A program is a few kB; a peer that sends without end is cut off at a bound.
  constexpr std::size_t kMostBytes = 1 << 20;
  while (!closed_ && buffer_.size() < kMostBytes &&
         hardware::monotonicSeconds() - last_byte_s < idle_s) {
    const std::size_t before = buffer_.size();
    if (!fill(kPollMs)) {
      break;
    }
    if (buffer_.size() != before) {
      last_byte_s = hardware::monotonicSeconds();
    }
  }
  return std::move(buffer_);
}

void TextConnection::write(const std::string& text) {
  (void)::send(socket_, text.data(), text.size(), MSG_NOSIGNAL);
}

TextPort::TextPort(const std::string& address, std::uint16_t port, const std::string& what,
                   Handler handler)
    : handler_(std::move(handler)) {
  sockaddr_in endpoint{};
  endpoint.sin_family = AF_INET;
  endpoint.sin_port = htons(port);
  const std::string where = address + ":" + std::to_string(port);
  if (inet_pton(AF_INET, address.c_str(), &endpoint.sin_addr) != 1) {
    throw std::runtime_error(what + ": \"" + address + "\" is not an IPv4 address");
  }
  listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int on = 1;
  ::setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (listener_ < 0 ||
      ::bind(listener_, reinterpret_cast<const sockaddr*>(&endpoint), sizeof endpoint) != 0 ||
      ::listen(listener_, 4) != 0) {
    const std::string why = std::strerror(errno);
    if (listener_ >= 0) {
      ::close(listener_);
    }
    throw std::runtime_error(what + " cannot listen on " + where + ": " + why);
  }
  socklen_t size = sizeof endpoint;
  ::getsockname(listener_, reinterpret_cast<sockaddr*>(&endpoint), &size);
  port_ = ntohs(endpoint.sin_port);
  thread_ = std::thread([this] { serve(); });
}

TextPort::~TextPort() {
  stopping_.store(true, std::memory_order_relaxed);
  thread_.join();
  ::close(listener_);
}

void TextPort::serve() {
  while (!stopping_.load(std::memory_order_relaxed)) {
    if (!readable(listener_, kPollMs)) {
      continue;
    }
    const int socket = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
    if (socket < 0) {
      continue;
    }
    TextConnection connection(socket, stopping_);
    handler_(connection);
    ::close(socket);
  }
}

}  // namespace comply::ur
