// A TCP connection made within a time limit (tcp_connect.hpp).

#include "comply/hardware/tcp_connect.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace comply::hardware {

int connectTcp(const std::string& host, std::uint16_t port, double timeout_s, std::string& why) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  if (inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1) {
    why = "\"" + host + "\" is not an IPv4 address";
    return -1;
  }
  const int socket = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (socket < 0) {
    why = std::strerror(errno);
    return -1;
  }
  int error = 0;
  if (::connect(socket, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = errno;
    if (error == EINPROGRESS) {
      pollfd writable{socket, POLLOUT, 0};
      const int ready =
          ::poll(&writable, 1, static_cast<int>(std::ceil(std::max(timeout_s, 0.0) * 1e3)));
      socklen_t size = sizeof error;
      error = ready > 0 ? 0 : (ready == 0 ? ETIMEDOUT : errno);
      if (ready > 0) {
        ::getsockopt(socket, SOL_SOCKET, SO_ERROR, &error, &size);
      }
    }
  }
  if (error != 0) {
    why = std::strerror(error);
    ::close(socket);
    return -1;
  }
  ::fcntl(socket, F_SETFL, ::fcntl(socket, F_GETFL, 0) & ~O_NONBLOCK);  // blocking from here
  return socket;
}

}  // namespace comply::hardware
