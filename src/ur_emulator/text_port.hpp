#pragma once
// A TCP port that serves one text connection at a time on a thread of its own (the emulated
// controller's secondary interface and dashboard): POSIX sockets, a poll with a short timeout so
// that the port stops promptly.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

namespace comply::ur {

/// One connection's text, read and written by its handler.
class TextConnection {
 public:
  TextConnection(int socket, const std::atomic<bool>& stopping)
      : socket_(socket), stopping_(stopping) {}
  /// The next line without its end ("\n", "\r\n"); false when the peer closed or the port stops.
  bool readLine(std::string& line);
  /// Everything until the peer closes its side, or `idle_s` without a byte (at most 1 MiB).
  std::string readAll(double idle_s);
  void write(const std::string& text);

 private:
  /// More bytes into buffer_; false at the end.
  bool fill(int timeout_ms);

  int socket_;
  const std::atomic<bool>& stopping_;
  std::string buffer_;
  bool closed_ = false;
};

class TextPort {
 public:
  using Handler = std::function<void(TextConnection&)>;
  /// Listens on `address`:`port` (0: any free port); throws std::runtime_error naming `what`.
  TextPort(const std::string& address, std::uint16_t port, const std::string& what,
           Handler handler);
  ~TextPort();
  TextPort(const TextPort&) = delete;
  TextPort& operator=(const TextPort&) = delete;
  [[nodiscard]] std::uint16_t port() const noexcept { return port_; }

 private:
  void serve();

  int listener_ = -1;
  std::uint16_t port_ = 0;
  Handler handler_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace comply::ur
