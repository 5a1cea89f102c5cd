#pragma once
// The supervision of the transport process (process_transport.hpp): starts comply-transport on
// one end of a socket pair, reads and watches it, ends it when it ends, breaks its stream or stops
// answering, and starts it again after a delay that grows while it keeps failing. Its frames are
// handled by IncomingFrames (frame_adapter.hpp). Private to the transport.

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "comply/transport/host_transport.hpp"
#include "comply/transport/process_transport.hpp"
#include "frame_adapter.hpp"

namespace comply::transport::process {

/// One transport process at a time. The reading side (everything but wake(), send() and the
/// counters) is for one thread at a time: the host transport's reader lock.
class ProcessSupervisor {
 public:
  /// Throws TransportError when the wake-up descriptor cannot be made; starts nothing.
  ProcessSupervisor(HostTransportOptions options, ProcessTransportOptions process);
  /// Ends the process for good.
  ~ProcessSupervisor();
  ProcessSupervisor(const ProcessSupervisor&) = delete;
  ProcessSupervisor& operator=(const ProcessSupervisor&) = delete;

  /// The first start, waited for until the process is ready: the samples it sends meanwhile go
  /// into `held`. Throws TransportError, with the inner transport's own error when it said one.
  void startAndWait(Inbox& held, std::vector<std::uint64_t>& departed);
  /// Waits up to `timeout_s` for frames (or a wake), reads everything waiting and handles it
  /// (samples into `inbox`). Ends the process when it ended, broke its stream or stopped
  /// answering (printed when `report`), its writers then appended to `departed`.
  void watch(Inbox& inbox, std::vector<std::uint64_t>& departed, double timeout_s, bool report);
  /// While the process is down: waits up to `timeout_s` for its restart time (or a wake), or
  /// starts it again when that time has come.
  void restartWhenDue(double timeout_s);
  [[nodiscard]] bool running() const noexcept { return pid_ > 0; }

  /// Any thread: watch() and restartWhenDue() return now.
  void wake();
  /// Any thread: sends the frame `encode()` makes, made with the socket's lock held so that the
  /// buffers it is made in serve every sending thread. False when the process is down, stuck, or
  /// did not take it within the send timeout (it is then marked stuck: watch() kills it).
  template <typename Encode>
  bool send(Encode&& encode) {
    const std::lock_guard<std::mutex> lock(send_mutex_);
    return sendLocked(encode());
  }

  [[nodiscard]] IncomingFrames& frames() noexcept { return frames_; }
  [[nodiscard]] const IncomingFrames& frames() const noexcept { return frames_; }
  [[nodiscard]] const std::filesystem::path& program() const noexcept { return process_.program; }
  [[nodiscard]] std::uint64_t restarts() const noexcept { return restarts_.load(); }

 private:
  using Clock = std::chrono::steady_clock;

  std::ostream& log() const;
  std::vector<std::string> arguments() const;
  void spawn();
  void spawnAgain();
  void scheduleRestart();
  bool readAvailable();
  void reportBack();
  void endChild(std::vector<std::uint64_t>& departed, std::string why, bool kill, bool report);
  int reap(bool kill);
  void stopChild();
  void waitForWake(double timeout_s);
  void drainWake();
  bool sendLocked(const std::vector<std::uint8_t>& bytes);

  HostTransportOptions options_;
  ProcessTransportOptions process_;
  int wake_fd_ = -1;

  // The reading side.
  pid_t pid_ = -1;
  Clock::time_point started_;
  Clock::time_point last_heard_;
  Clock::time_point last_read_;
  Clock::time_point next_start_;
  double restart_delay_s_;
  std::string last_end_;  ///< how the last process ended ("ended on signal 6 (Aborted)")
  IncomingFrames frames_;

  // The sending side (send(), and the socket's replacement): send_mutex_.
  std::mutex send_mutex_;
  int socket_ = -1;
  std::atomic<bool> stuck_{false};

  std::atomic<std::uint64_t> restarts_{0};
};

}  // namespace comply::transport::process
