#pragma once
// A UR controller's RTDE interface over TCP, as comply's UR controller emulator serves it: any
// number of clients, each with its own RtdeServerSession (version, recipes, start and pause). The
// emulator hands it the controller's variables every controller cycle (sendOutputs(), at the
// controller's rate); each started client gets its output recipe filled from them, at its own
// frequency. What clients write to their inputs is kept by name (inputs()). One I/O thread.

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "comply/ur/rtde_server_session.hpp"

namespace comply::ur {

struct RtdeServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = kRtdePort;  ///< 0: any free port (port() tells)
  ControllerVersion version{5, 23, 0, 0};
  /// The controller's cycle rate: sendOutputs() is called this often, the fastest recipe.
  double max_frequency_hz = 500.0;
  /// SCHED_FIFO priority of the I/O thread (0: normal), where the process may have it.
  int thread_priority = 0;
};

class RtdeServer {
 public:
  /// Listens; throws RtdeError naming the address when it cannot.
  explicit RtdeServer(const RtdeServerOptions& options);
  ~RtdeServer();
  RtdeServer(const RtdeServer&) = delete;
  RtdeServer& operator=(const RtdeServer&) = delete;

  [[nodiscard]] std::uint16_t port() const noexcept;
  /// One controller cycle's variables, by name: every started client's output recipe is filled
  /// from them (a variable missing, or of another type, goes as zero) when its frequency is due.
  /// Any thread; never waits for a client.
  void sendOutputs(const std::map<std::string, RtdeValue>& variables);
  /// What the clients last wrote to each input, by name.
  [[nodiscard]] std::map<std::string, RtdeValue> inputs() const;
  /// When the last data package's bytes were handed to a client's socket (monotonic seconds,
  /// hardware::monotonicSeconds()); 0 before any.
  [[nodiscard]] double lastOutputWritten() const;
  /// Input data packages received from all clients so far.
  [[nodiscard]] std::uint64_t inputPackages() const;
  /// Waits until inputPackages() exceeds `seen`, at most `timeout_s`; false on the timeout.
  bool awaitInputs(std::uint64_t seen, double timeout_s);
  /// Closes every client's connection (a cable pulled): they may connect again.
  void closeConnections();
  /// Clients connected now.
  [[nodiscard]] std::size_t connections() const;

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace comply::ur
