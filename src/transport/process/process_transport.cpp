// The host's side of a transport in its own process (see process_transport.hpp): starts
// comply-transport on one end of a socket pair, turns its frames into the Inbox, sends it the
// state and diagnostics, and starts it again when it ends or stops answering.

#include "comply/transport/process_transport.hpp"

#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "comply/core/install_paths.hpp"
#include "comply/transport/cdr.hpp"
#include "frames.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX declares it nowhere

namespace comply::transport {
namespace {

using Clock = std::chrono::steady_clock;
using process::Frame;
using process::FrameKind;

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

std::string describeEnd(int status) {
  std::ostringstream text;
  if (status == -1) {
    text << "ended (its exit status could not be read)";
  } else if (WIFSIGNALED(status)) {
    const char* name = strsignal(WTERMSIG(status));
    text << "ended on signal " << WTERMSIG(status) << " (" << (name != nullptr ? name : "?") << ")";
  } else if (WIFEXITED(status)) {
    text << "exited with code " << WEXITSTATUS(status);
  } else {
    text << "ended";
  }
  return text.str();
}

class ProcessHostTransport final : public HostTransport {
 public:
  ProcessHostTransport(HostTransportOptions options, ProcessTransportOptions process)
      : options_(std::move(options)), process_(std::move(process)) {
    if (process_.program.empty()) {
      process_.program = transportProgram();
    }
    wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (wake_fd_ < 0) {
      throw TransportError(std::string("transport process: eventfd: ") + std::strerror(errno));
    }
    try {
      spawn();
    } catch (...) {
      ::close(wake_fd_);
      throw;
    }
    // The first start is waited for: an error of the inner transport is the host's start-up error.
    Inbox held;
    while (!ready_ && child_pid_ > 0) {
      readFromChild(held, 0.05, /*report=*/false);
    }
    if (!ready_) {
      const std::string why = !failure_.empty() ? failure_
                              : !last_end_.empty()
                                  ? "the transport process " + last_end_ + " before it was ready"
                                  : "the transport process did not start";
      stopChild();
      ::close(wake_fd_);
      throw TransportError(why);
    }
    pending_ = std::move(held);
  }

  ~ProcessHostTransport() override {
    stopChild();
    ::close(wake_fd_);
  }
  ProcessHostTransport(const ProcessHostTransport&) = delete;
  ProcessHostTransport& operator=(const ProcessHostTransport&) = delete;

  void receive(Inbox& inbox, double timeout_s) override {
    const std::lock_guard<std::mutex> lock(read_mutex_);
    appendPending(inbox);
    if (child_pid_ < 0) {
      // Down: wait for the restart time (or a wake), then start it again.
      const double until_restart =
          std::chrono::duration<double>(next_start_ - Clock::now()).count();
      if (until_restart > 0.0) {
        waitForWake(std::min(timeout_s, until_restart));
        return;
      }
      spawnAgain();
      return;
    }
    readFromChild(inbox, timeout_s, /*report=*/true);
  }

  void wake() override {
    const std::uint64_t one = 1;
    (void)!::write(wake_fd_, &one, sizeof(one));
  }

  void publish(const ControllerStateMessage& state) override {
    sendEncoded(FrameKind::kState, state);
  }

  void publish(const DiagnosticsMessage& diagnostics) override {
    sendEncoded(FrameKind::kDiagnostics, diagnostics);
  }

  bool flush(double timeout_s) override {
    const std::lock_guard<std::mutex> lock(read_mutex_);
    {
      const std::lock_guard<std::mutex> send_lock(send_mutex_);
      std::vector<std::uint8_t> frame;
      std::vector<std::uint8_t> payload(sizeof(double));
      std::memcpy(payload.data(), &timeout_s, sizeof(double));
      process::appendFrame(FrameKind::kFlush, payload, frame);
      flushed_.reset();
      if (!sendLocked(frame)) {
        return false;
      }
    }
    // The answer comes after the process's own wait, plus the hop back.
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s + 0.5);
    while (!flushed_ && child_pid_ > 0 && Clock::now() < deadline) {
      readFromChild(pending_, 0.05, /*report=*/true);
    }
    return flushed_.value_or(false);
  }

  [[nodiscard]] std::string describe() const override {
    const std::lock_guard<std::mutex> lock(describe_mutex_);
    return description_ + " in its own process (" + process_.program.string() + ")";
  }

  [[nodiscard]] std::uint64_t malformedSamples() const override {
    return malformed_ended_.load() + malformed_current_.load();
  }
  [[nodiscard]] std::uint64_t restarts() const override { return restarts_.load(); }

 private:
  std::ostream& log() const { return process_.log != nullptr ? *process_.log : std::cerr; }

  /// Starts the process on a new socket pair. Throws TransportError when it cannot be started.
  void spawn() {
    std::array<int, 2> pair{};
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair.data()) != 0) {
      throw TransportError(std::string("transport process: socketpair: ") + std::strerror(errno));
    }
    const timeval send_timeout{0, static_cast<suseconds_t>(kSendTimeoutS * 1e6)};
    ::setsockopt(pair[0], SOL_SOCKET, SO_SNDTIMEO, &send_timeout, sizeof(send_timeout));

    const std::vector<std::string> args = {process_.program.string(),
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
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (const std::string& arg : args) {
      argv.push_back(const_cast<char*>(arg.c_str()));
    }
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    // dup2 onto the fixed number clears close-on-exec there (and glibc clears it when the numbers
    // are equal too); every other descriptor of the host stays closed in the child.
    posix_spawn_file_actions_adddup2(&actions, pair[1], kChildSocketFd);
    // Normal scheduling and signals whatever the spawning thread has (a restart comes from the
    // host's reader thread, which may run SCHED_FIFO): the process raises its own receiving
    // threads to options_.receive_priority, and a hung one cannot starve the host that watches it.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t no_signals;
    sigemptyset(&no_signals);
    sigset_t default_signals;  // what the host may ignore that the process must not
    sigemptyset(&default_signals);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGCHLD, SIGALRM}) {
      sigaddset(&default_signals, signal);
    }
    sched_param normal{};
    posix_spawnattr_setsigmask(&attributes, &no_signals);
    posix_spawnattr_setsigdefault(&attributes, &default_signals);
    posix_spawnattr_setschedpolicy(&attributes, SCHED_OTHER);
    posix_spawnattr_setschedparam(&attributes, &normal);
    posix_spawnattr_setflags(
        &attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSCHEDULER);
    pid_t pid = -1;
    const int error =
        posix_spawn(&pid, process_.program.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pair[1]);
    if (error != 0) {
      ::close(pair[0]);
      throw TransportError("cannot start the transport program " + process_.program.string() +
                           ": " + std::strerror(error));
    }
    {
      const std::lock_guard<std::mutex> lock(send_mutex_);
      child_fd_ = pair[0];
      stuck_ = false;
    }
    child_pid_ = pid;
    started_ = Clock::now();
    last_heard_ = started_;
    last_read_ = started_;
    frames_ = process::FrameReader();
    frames_broken_ = false;
    ready_ = false;
    failure_.clear();
    malformed_current_ = 0;
  }

  void spawnAgain() {
    try {
      spawn();
      ++restarts_;
    } catch (const TransportError& error) {
      log() << "comply: transport: " << error.what() << "; trying again in " << restart_delay_s_
            << " s\n";
      scheduleRestart();
    }
  }

  void scheduleRestart() {
    next_start_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(restart_delay_s_));
    restart_delay_s_ = std::min(2.0 * restart_delay_s_, kMaxRestartDelayS);
  }

  /// Waits up to `timeout_s` for frames (or a wake), reads everything waiting and handles it.
  void readFromChild(Inbox& inbox, double timeout_s, bool report) {
    // Silence counts only while the host itself ran: after a gap between two reads (the host
    // stopped, or suspended with its transport) the process gets a full period to be heard.
    const auto now = Clock::now();
    if (now - last_read_ > std::chrono::duration<double>(0.5 * process_.heartbeat_timeout_s)) {
      last_heard_ = now;
    }
    std::array<pollfd, 2> fds{pollfd{child_fd_, POLLIN, 0}, pollfd{wake_fd_, POLLIN, 0}};
    const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(timeout_s * 1000.0));
    if (ready > 0 && (fds[1].revents & POLLIN) != 0) {
      std::uint64_t count = 0;
      (void)!::read(wake_fd_, &count, sizeof(count));
    }
    bool ended = false;
    if (ready > 0 && fds[0].revents != 0) {
      ended = !readAvailable();
    }
    while (auto frame = frames_.next()) {
      handle(*frame, inbox);
    }
    if (frames_.broken() || frames_broken_) {
      endChild("sent a frame comply cannot read", /*kill=*/true, report);
    } else if (ended) {
      endChild("", /*kill=*/false, report);
    } else if (!ready_ && secondsSince(started_) > process_.start_timeout_s) {
      // Before it is ready it sends nothing (its participant may take a while, DDS Security's
      // handshake more): the start has its own, longer deadline.
      std::ostringstream why;
      why << "was not ready " << process_.start_timeout_s << " s after its start and was killed";
      endChild(why.str(), /*kill=*/true, report);
    } else if (ready_ &&
               (stuck_.load() || secondsSince(last_heard_) > process_.heartbeat_timeout_s)) {
      std::ostringstream why;
      why << "stopped answering for " << std::fixed << std::setprecision(1)
          << secondsSince(last_heard_) << " s and was killed";
      endChild(why.str(), /*kill=*/true, report);
    }
    last_read_ = Clock::now();
  }

  /// Reads what waits on the socket; false at its end (the process closed it or ended).
  bool readAvailable() {
    std::array<std::uint8_t, 1U << 16U> buffer{};
    for (;;) {
      const ssize_t n = ::recv(child_fd_, buffer.data(), buffer.size(), MSG_DONTWAIT);
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

  /// `message` in CDR, in one frame of `kind` to the process.
  template <typename Message>
  void sendEncoded(FrameKind kind, const Message& message) {
    const std::lock_guard<std::mutex> lock(send_mutex_);
    encodeCdr(message, cdr_);
    out_.clear();
    process::appendFrame(kind, cdr_, out_);
    sendLocked(out_);
  }

  template <typename Message>
  void take(const Frame& frame, std::vector<Sample<Message>>& into) {
    Sample<Message> sample;
    if (process::readSampleFrame(frame.payload, sample)) {
      publishers_.insert(sample.publisher);
      into.push_back(std::move(sample));
    } else {
      frames_broken_ = true;
    }
  }

  void handle(const Frame& frame, Inbox& inbox) {
    switch (frame.kind) {
      case FrameKind::kReady: {
        const std::lock_guard<std::mutex> lock(describe_mutex_);
        description_ = process::readText(frame.payload);
        ready_ = true;
        if (restarts_.load() > 0) {
          log() << "comply: the transport process is back (pid " << child_pid_ << ", restart "
                << restarts_.load() << ")\n"
                << std::flush;
        }
        break;
      }
      case FrameKind::kFailed:
        failure_ = process::readText(frame.payload);
        break;
      case FrameKind::kDeparted:
        if (const auto writer = process::readU64(frame.payload)) {
          publishers_.erase(*writer);
          inbox.departed.push_back(*writer);
        }
        break;
      case FrameKind::kHeartbeat:
        if (const auto malformed = process::readU64(frame.payload)) {
          malformed_current_ = *malformed;
        }
        break;
      case FrameKind::kFlushed:
        flushed_ = !frame.payload.empty() && frame.payload[0] != 0;
        break;
      default:
        takeSample(frame, inbox);
        break;
    }
  }

  /// A sample frame into its topic's list; any other kind breaks the stream.
  void takeSample(const Frame& frame, Inbox& inbox) {
    bool taken = false;
    forEachTopic(inbox.topics(), [&](int topic, auto& samples) {
      if (frame.kind == process::sampleFrameKind(topic)) {
        take(frame, samples);
        taken = true;
      }
    });
    if (!taken) {
      frames_broken_ = true;
    }
  }

  /// The process is gone or is to go: reaps it, reports why, and lets go of every writer it had
  /// seen (a restarted process sees them anew, under other handles).
  void endChild(std::string why, bool kill, bool report) {
    const pid_t pid = child_pid_;
    const int status = reap(kill);
    {
      const std::lock_guard<std::mutex> lock(send_mutex_);
      ::close(child_fd_);
      child_fd_ = -1;
    }
    malformed_ended_ += malformed_current_.exchange(0);
    for (const std::uint64_t writer : publishers_) {
      pending_.departed.push_back(writer);
    }
    publishers_.clear();
    if (secondsSince(started_) > kQuickEndS) {
      restart_delay_s_ = process_.restart_delay_s;
    }
    scheduleRestart();
    last_end_ = describeEnd(status);
    if (!failure_.empty()) {
      why = why.empty() ? failure_ : why + "; " + failure_;
    }
    if (report) {
      log() << "comply: the transport process (" << process_.inner << ", pid " << pid << ") "
            << (why.empty() ? last_end_ : why + "; " + last_end_)
            << ": no commands arrive until it is back (the watchdog holds the arm); starting it "
               "again\n"
            << std::flush;
    }
  }

  /// Waits for the process to end (killing it when `kill`, or when it will not end in 1 s);
  /// its wait status.
  int reap(bool kill) {
    int status = 0;
    if (child_pid_ <= 0) {
      return status;
    }
    if (kill) {
      ::kill(child_pid_, SIGKILL);
    }
    const auto deadline = Clock::now() + std::chrono::seconds(1);
    for (;;) {
      const pid_t reaped = ::waitpid(child_pid_, &status, WNOHANG);
      if (reaped == child_pid_) {
        break;
      }
      if (reaped < 0 && errno != EINTR) {
        // Not ours to reap (SIGCHLD ignored by the program embedding the host): gone, cause
        // unknown.
        status = -1;
        break;
      }
      if (Clock::now() > deadline) {
        ::kill(child_pid_, SIGKILL);
        while (::waitpid(child_pid_, &status, 0) < 0 && errno == EINTR) {
        }
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    child_pid_ = -1;
    return status;
  }

  /// Ends the process for good: its socket closed is its signal to stop.
  void stopChild() {
    {
      const std::lock_guard<std::mutex> lock(send_mutex_);
      if (child_fd_ >= 0) {
        ::shutdown(child_fd_, SHUT_RDWR);
        ::close(child_fd_);
        child_fd_ = -1;
      }
    }
    reap(/*kill=*/false);
  }

  void appendPending(Inbox& inbox) {
    if (pending_.empty()) {
      return;
    }
    const auto move_all = [](auto& from, auto& to) {
      for (auto& item : from) {
        to.push_back(std::move(item));
      }
      from.clear();
    };
    move_all(pending_.cartesian, inbox.cartesian);
    move_all(pending_.joint, inbox.joint);
    move_all(pending_.cartesian_chunks, inbox.cartesian_chunks);
    move_all(pending_.joint_chunks, inbox.joint_chunks);
    move_all(pending_.requests, inbox.requests);
    move_all(pending_.departed, inbox.departed);
  }

  void waitForWake(double timeout_s) {
    pollfd fd{wake_fd_, POLLIN, 0};
    if (::poll(&fd, 1, static_cast<int>(timeout_s * 1000.0)) > 0) {
      std::uint64_t count = 0;
      (void)!::read(wake_fd_, &count, sizeof(count));
    }
  }

  /// Writes `bytes` whole, with send_mutex_ held. A process that does not take them within
  /// kSendTimeoutS is marked stuck (the reader kills it); a frame cut short leaves the stream
  /// unreadable, so it is marked too.
  bool sendLocked(const std::vector<std::uint8_t>& bytes) {
    if (child_fd_ < 0 || stuck_.load()) {
      return false;
    }
    if (!process::sendAll(child_fd_, bytes)) {
      stuck_ = true;
      wake();
      return false;
    }
    return true;
  }

  HostTransportOptions options_;
  ProcessTransportOptions process_;
  int wake_fd_ = -1;

  // The reading side (receive, flush): read_mutex_.
  std::mutex read_mutex_;
  pid_t child_pid_ = -1;
  Clock::time_point started_;
  Clock::time_point last_heard_;
  Clock::time_point last_read_;
  Clock::time_point next_start_;
  double restart_delay_s_ = process_.restart_delay_s;
  process::FrameReader frames_;
  bool frames_broken_ = false;
  bool ready_ = false;
  std::string failure_;
  std::string last_end_;  ///< how the last process ended ("ended on signal 6 (Aborted)")
  std::optional<bool> flushed_;
  std::set<std::uint64_t> publishers_;  ///< writers seen from the current process
  Inbox pending_;  ///< taken outside receive() (start-up, flush, an ended process's writers)

  // The sending side (publish, and the socket's replacement): send_mutex_.
  std::mutex send_mutex_;
  int child_fd_ = -1;
  std::vector<std::uint8_t> cdr_;
  std::vector<std::uint8_t> out_;
  std::atomic<bool> stuck_{false};

  mutable std::mutex describe_mutex_;
  std::string description_;
  std::atomic<std::uint64_t> malformed_ended_{0};
  std::atomic<std::uint64_t> malformed_current_{0};
  std::atomic<std::uint64_t> restarts_{0};
};

}  // namespace

std::unique_ptr<HostTransport> makeProcessHostTransport(const HostTransportOptions& options,
                                                        ProcessTransportOptions process) {
  return std::make_unique<ProcessHostTransport>(options, std::move(process));
}

std::filesystem::path transportProgram() {
  if (const char* env = std::getenv("COMPLY_TRANSPORT_PROGRAM"); env != nullptr && *env != 0) {
    return env;
  }
  if (const auto installed = installedFolder(COMPLY_TRANSPORT_RELDIR)) {
    auto program = *installed / "comply-transport";
    std::error_code error;
    if (std::filesystem::is_regular_file(program, error)) {
      return program;
    }
  }
  return COMPLY_BUILD_TRANSPORT_PROGRAM;
}

}  // namespace comply::transport
