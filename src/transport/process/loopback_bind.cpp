// bind() for comply-transport (see loopback_bind.hpp).

#include "loopback_bind.hpp"

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

namespace comply::transport::process {
namespace {

std::atomic<bool> loopback_only{false};

}  // namespace

void bindLoopbackOnly() {
  loopback_only = true;
}

}  // namespace comply::transport::process

// NOLINTNEXTLINE(readability-inconsistent-declaration-parameter-name): POSIX's own declaration
extern "C" int bind(int socket, const sockaddr* address, socklen_t length) {
  if (comply::transport::process::loopback_only.load() && address != nullptr &&
      address->sa_family == AF_INET && length >= sizeof(sockaddr_in)) {
    sockaddr_in local{};
    std::memcpy(&local, address, sizeof(local));
    if (local.sin_addr.s_addr == htonl(INADDR_ANY)) {
      local.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      return static_cast<int>(::syscall(SYS_bind, socket, &local, sizeof(local)));
    }
  }
  return static_cast<int>(::syscall(SYS_bind, socket, address, length));
}
