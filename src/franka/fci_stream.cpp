// The FCI command port's byte stream (fci_stream.hpp).

#include "comply/franka/fci_stream.hpp"

#include <poll.h>
#include <sys/socket.h>

#include <cerrno>

namespace comply::franka {

bool readExactly(int socket, std::uint8_t* out, std::size_t bytes, const std::stop_token& stop) {
  std::size_t done = 0;
  while (done < bytes) {
    pollfd readable{socket, POLLIN, 0};
    const int ready = ::poll(&readable, 1, 50);
    if (stop.stop_requested()) {
      return false;
    }
    if (ready <= 0) {
      continue;
    }
    const ssize_t got = ::recv(socket, out + done, bytes - done, 0);
    if (got <= 0) {
      if (got < 0 && (errno == EINTR || errno == EAGAIN)) {
        continue;
      }
      return false;
    }
    done += static_cast<std::size_t>(got);
  }
  return true;
}

}  // namespace comply::franka
