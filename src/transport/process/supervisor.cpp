// The transport process's supervision (see supervisor.hpp).

#include "supervisor.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "child_process.hpp"

namespace comply::transport::process {
namespace {

using Clock = std::chrono::steady_clock;

/// The socket's number in the transport process.
constexpr int kChildSocketFd = 3;
/// A send that cannot finish in this long means the process does not read: it is hung.
constexpr double kSendTimeoutS = 0.25;
/// A process that ends sooner than this after its start counts as failing to start.
constexpr double kQuickEndS = 2.0;
constexpr double kMaxRestartDelayS = 8.0;

double secondsSince(Clock::time_point then) {
  return std::chrono::duration<double>(Clock::now() - then).count();
}

}  // namespace

ProcessSupervisor::ProcessSupervisor(HostTransportOptions options, ProcessTransportOptions process)
    : options_(std::move(options)),
      process_(std::move(process)),
      restart_delay_s_(process_.restart_delay_s) {
  if (process_.program.empty()) {
    process_.program = transportProgram();
  }
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) {
    throw TransportError(std::string("transport process: eventfd: ") + std::strerror(errno));
  }
}

ProcessSupervisor::~ProcessSupervisor() {
  stopChild();
  ::close(wake_fd_);
}

void ProcessSupervisor::startAndWait(Inbox& held, std::vector<std::uint64_t>& departed) {
  spawn();
  while (!frames_.ready() && pid_ > 0) {
    watch(held, departed, 0.05, /*report=*/false);
  }
  if (!frames_.ready()) {
    throw TransportError(!frames_.failure().empty() ? frames_.failure()
                         : !last_end_.empty()
                             ? "the transport process " + last_end_ + " before it was ready"
                             : "the transport process did not start");
  }
}

void ProcessSupervisor::watch(Inbox& inbox, std::vector<std::uint64_t>& departed, double timeout_s,
                              bool report) {
  // Silence counts only while the host itself ran: after a gap between two reads (the host
  // stopped, or suspended with its transport) the process gets a full period to be heard.
  const auto now = Clock::now();
  if (now - last_read_ > std::chrono::duration<double>(0.5 * process_.heartbeat_timeout_s)) {
    last_heard_ = now;
  }
  std::array<pollfd, 2> fds{pollfd{socket_, POLLIN, 0}, pollfd{wake_fd_, POLLIN, 0}};
  const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(timeout_s * 1000.0));
  if (ready > 0 && (fds[1].revents & POLLIN) != 0) {
    drainWake();
  }
  bool ended = false;
  if (ready > 0 && fds[0].revents != 0) {
    ended = !readAvailable();
  }
  while (const auto kind = frames_.handleNext(inbox)) {
    if (*kind == FrameKind::kReady) {
      reportBack();
    }
  }
  if (frames_.broken()) {
    endChild(departed, "sent a frame comply cannot read", /*kill=*/true, report);
  } else if (ended) {
    endChild(departed, "", /*kill=*/false, report);
  } else if (!frames_.ready() && secondsSince(started_) > process_.start_timeout_s) {
    // Before it is ready it sends nothing (its participant may take a while, DDS Security's
    // handshake more): the start has its own, longer deadline.
    std::ostringstream why;
    why << "was not ready " << process_.start_timeout_s << " s after its start and was killed";
    endChild(departed, why.str(), /*kill=*/true, report);
  } else if (frames_.ready() &&
             (stuck_.load() || secondsSince(last_heard_) > process_.heartbeat_timeout_s)) {
    std::ostringstream why;
    why << "stopped answering for " << std::fixed << std::setprecision(1)
        << secondsSince(last_heard_) << " s and was killed";
    endChild(departed, why.str(), /*kill=*/true, report);
  }
  last_read_ = Clock::now();
}

void ProcessSupervisor::restartWhenDue(double timeout_s) {
  const double until_restart = std::chrono::duration<double>(next_start_ - Clock::now()).count();
  if (until_restart > 0.0) {
    waitForWake(std::min(timeout_s, until_restart));
    return;
  }
  spawnAgain();
}

void ProcessSupervisor::wake() {
  const std::uint64_t one = 1;
  (void)!::write(wake_fd_, &one, sizeof(one));
}

std::ostream& ProcessSupervisor::log() const {
  return process_.log != nullptr ? *process_.log : std::cerr;
}

/// comply-transport's command line.
std::vector<std::string> ProcessSupervisor::arguments() const {
  return {process_.program.string(),
          "--fd",
          std::to_string(kChildSocketFd),
          "--transport",
          process_.inner,
          "--name",
          options_.name,
          "--domain",
          std::to_string(options_.domain_id),
          "--network",
          options_.network,
          "--priority",
          std::to_string(options_.receive_priority),
          "--security",
          options_.security.string()};
}

/// Starts the process on a new socket pair. Throws TransportError when it cannot be started.
void ProcessSupervisor::spawn() {
  const ChildWithSocket child = spawnWithSocket(arguments(), kChildSocketFd, kSendTimeoutS);
  {
    const std::lock_guard<std::mutex> lock(send_mutex_);
    socket_ = child.socket;
    stuck_ = false;
  }
  pid_ = child.pid;
  started_ = Clock::now();
  last_heard_ = started_;
  last_read_ = started_;
  frames_.restart();
}

void ProcessSupervisor::spawnAgain() {
  try {
    spawn();
    ++restarts_;
  } catch (const TransportError& error) {
    log() << "comply: transport: " << error.what() << "; trying again in " << restart_delay_s_
          << " s\n";
    scheduleRestart();
  }
}

void ProcessSupervisor::scheduleRestart() {
  next_start_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(restart_delay_s_));
  restart_delay_s_ = std::min(2.0 * restart_delay_s_, kMaxRestartDelayS);
}

/// Reads what waits on the socket; false at its end (the process closed it or ended).
bool ProcessSupervisor::readAvailable() {
  std::array<std::uint8_t, 1U << 16U> buffer{};
  for (;;) {
    const ssize_t n = ::recv(socket_, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n > 0) {
      frames_.append({buffer.data(), static_cast<std::size_t>(n)});
      last_heard_ = Clock::now();
      continue;
    }
    if (n < 0 && errno == EINTR) {
      continue;
    }
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
}

/// A restarted process said it is ready.
void ProcessSupervisor::reportBack() {
  if (restarts_.load() > 0) {
    log() << "comply: the transport process is back (pid " << pid_ << ", restart "
          << restarts_.load() << ")\n"
          << std::flush;
  }
}

/// The process is gone or is to go: reaps it, reports why, and lets go of every writer it had
/// seen.
void ProcessSupervisor::endChild(std::vector<std::uint64_t>& departed, std::string why, bool kill,
                                 bool report) {
  const pid_t pid = pid_;
  const int status = reap(kill);
  {
    const std::lock_guard<std::mutex> lock(send_mutex_);
    ::close(socket_);
    socket_ = -1;
  }
  frames_.processEnded(departed);
  if (secondsSince(started_) > kQuickEndS) {
    restart_delay_s_ = process_.restart_delay_s;
  }
  scheduleRestart();
  last_end_ = describeEnd(status);
  if (!frames_.failure().empty()) {
    why = why.empty() ? frames_.failure() : why + "; " + frames_.failure();
  }
  if (report) {
    log() << "comply: the transport process (" << process_.inner << ", pid " << pid << ") "
          << (why.empty() ? last_end_ : why + "; " + last_end_)
          << ": no commands arrive until it is back (the watchdog holds the arm); starting it "
             "again\n"
          << std::flush;
  }
}

int ProcessSupervisor::reap(bool kill) {
  const int status = reapChild(pid_, kill);
  pid_ = -1;
  return status;
}

/// Ends the process for good: its socket closed is its signal to stop.
void ProcessSupervisor::stopChild() {
  {
    const std::lock_guard<std::mutex> lock(send_mutex_);
    if (socket_ >= 0) {
      ::shutdown(socket_, SHUT_RDWR);
      ::close(socket_);
      socket_ = -1;
    }
  }
  reap(/*kill=*/false);
}

void ProcessSupervisor::waitForWake(double timeout_s) {
  pollfd fd{wake_fd_, POLLIN, 0};
  if (::poll(&fd, 1, static_cast<int>(timeout_s * 1000.0)) > 0) {
    drainWake();
  }
}

/// Takes the wakes counted so far, so that the next wait waits.
void ProcessSupervisor::drainWake() {
  std::uint64_t count = 0;
  (void)!::read(wake_fd_, &count, sizeof(count));
}

/// Writes `bytes` whole, with send_mutex_ held. A frame cut short leaves the stream unreadable,
/// so a process that does not take it whole is marked stuck too.
bool ProcessSupervisor::sendLocked(const std::vector<std::uint8_t>& bytes) {
  if (socket_ < 0 || stuck_.load()) {
    return false;
  }
  if (!sendAll(socket_, bytes)) {
    stuck_ = true;
    wake();
    return false;
  }
  return true;
}

}  // namespace comply::transport::process
