// comply-transport: a live host's middleware in a process of its own (process_transport.hpp).
// The host starts it with one end of a socket pair; it runs the transport named by --transport,
// sends the host every sample it receives and a heartbeat, and publishes what the host sends.
// It ends when the host closes the socket (or dies: the kernel then signals it).
//
//   comply-transport --fd N --transport dds --name NAME --domain ID --network loopback|all
//                    --priority P --security ENCLAVE_FOLDER (empty: none)

#include <malloc.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "comply/core/realtime_scheduling.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/dds_host_transport.hpp"
#include "frames.hpp"
#include "loopback_bind.hpp"

namespace {

using comply::transport::forEachTopic;
using comply::transport::HostTransport;
using comply::transport::HostTransportOptions;
using comply::transport::Inbox;
using comply::transport::process::appendFrame;
using comply::transport::process::appendSampleFrame;
using comply::transport::process::Frame;
using comply::transport::process::FrameKind;
using comply::transport::process::FrameReader;
using comply::transport::process::sampleFrameKind;

using Clock = std::chrono::steady_clock;
constexpr auto kHeartbeatPeriod = std::chrono::milliseconds(50);

/// The socket to the host, written from both threads.
class HostLink {
 public:
  explicit HostLink(int fd) : fd_(fd) {}
  /// False once the host is gone.
  bool send(const std::vector<std::uint8_t>& bytes) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return comply::transport::process::sendAll(fd_, bytes);
  }
  [[nodiscard]] int fd() const noexcept { return fd_; }

 private:
  int fd_;
  std::mutex mutex_;
};

/// What the host asked to publish, in order, for the publishing thread. The socket is always
/// drained (serveHost never waits on DDS), so a subscriber that holds a reliable writer back
/// cannot make the host's sends time out: the newest state replaces one not yet published, and
/// beyond kMaxWaiting the oldest waiting diagnostics (or answers) are dropped (counted, and said
/// once).
class Outbox {
 public:
  static constexpr std::size_t kMaxWaiting = 1000;

  struct Job {
    FrameKind kind{};
    std::vector<std::uint8_t> payload;
  };

  void push(Frame frame) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frame.kind == FrameKind::kState) {
      for (Job& job : jobs_) {
        if (job.kind == FrameKind::kState) {
          job.payload = std::move(frame.payload);
          return;
        }
      }
    }
    if (jobs_.size() >= kMaxWaiting) {
      for (auto it = jobs_.begin(); it != jobs_.end(); ++it) {
        if (it->kind != FrameKind::kFlush) {
          jobs_.erase(it);
          if (dropped_++ == 0) {
            std::fprintf(stderr,
                         "comply-transport: DDS takes the host's diagnostics slower than they "
                         "come (a subscriber holds the writer back); the oldest are dropped\n");
          }
          break;
        }
      }
    }
    jobs_.push_back({frame.kind, std::move(frame.payload)});
    ready_.notify_one();
  }
  /// The next job; nullopt once closed and empty.
  std::optional<Job> take() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return !jobs_.empty() || closed_; });
    if (jobs_.empty()) {
      return std::nullopt;
    }
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    return job;
  }
  void close() {
    const std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    ready_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Job> jobs_;
  std::uint64_t dropped_ = 0;
  bool closed_ = false;
};

/// The host's frames into `outbox`, until the end of the socket.
void serveHost(HostLink& link, Outbox& outbox) {
  FrameReader frames;
  std::array<std::uint8_t, 1U << 16U> buffer{};
  for (;;) {
    const ssize_t n = ::recv(link.fd(), buffer.data(), buffer.size(), 0);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      return;
    }
    frames.append({buffer.data(), static_cast<std::size_t>(n)});
    while (auto frame = frames.next()) {
      outbox.push(std::move(*frame));
    }
    if (frames.broken()) {
      return;
    }
  }
}

/// Publishes what the host sent, in order, until `outbox` is closed and empty.
void publishForHost(HostLink& link, HostTransport& transport, Outbox& outbox) {
  comply::transport::ControllerStateMessage state;
  comply::transport::DiagnosticsMessage diagnostics;
  comply::transport::CommittedMessage answer;
  while (auto job = outbox.take()) {
    if (job->kind == FrameKind::kState && comply::transport::decodeCdr(job->payload, state)) {
      transport.publish(state);
    } else if (job->kind == FrameKind::kDiagnostics &&
               comply::transport::decodeCdr(job->payload, diagnostics)) {
      transport.publish(diagnostics);
    } else if (job->kind == FrameKind::kCommitted &&
               comply::transport::decodeCdr(job->payload, answer)) {
      transport.publish(answer);
    } else if (job->kind == FrameKind::kFlush && job->payload.size() == sizeof(double)) {
      double timeout_s = 0.0;
      std::memcpy(&timeout_s, job->payload.data(), sizeof(double));
      const std::uint8_t delivered = transport.flush(timeout_s) ? 1 : 0;
      // The count first: the host's summary, printed after the flush, is then exact.
      std::vector<std::uint8_t> reply;
      appendFrame(FrameKind::kHeartbeat, transport.malformedSamples(), reply);
      appendFrame(FrameKind::kFlushed, std::span<const std::uint8_t>(&delivered, 1), reply);
      link.send(reply);
    } else {
      std::fprintf(stderr, "comply-transport: a frame from the host it cannot read (kind %d)\n",
                   static_cast<int>(job->kind));
    }
  }
}

/// What the transport receives, to the host: taken and sent at once from the middleware's own
/// thread where it can call us (one wake-up less on a command's way), else by the loop below.
class Forwarder {
 public:
  Forwarder(HostLink& link, HostTransport& transport) : link_(link), transport_(transport) {}

  /// Takes what waits (waiting up to `timeout_s` for it) and sends it, with a heartbeat when one
  /// is due; false once the host is gone.
  bool forward(double timeout_s) {
    if (timeout_s > 0.0) {
      transport_.receive(waiting_, timeout_s);  // alone: the middleware calls back only when told
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    inbox_.clear();
    out_.clear();
    transport_.receive(inbox_, 0.0);
    appendInbox(waiting_);
    appendInbox(inbox_);
    waiting_.clear();
    if (Clock::now() - last_heartbeat_ >= kHeartbeatPeriod) {
      appendFrame(FrameKind::kHeartbeat, transport_.malformedSamples(), out_);
      last_heartbeat_ = Clock::now();
    }
    return out_.empty() || link_.send(out_);
  }

 private:
  void appendInbox(const Inbox& inbox) {
    forEachTopic(inbox.topics(), [&](int topic, const auto& samples) {
      for (const auto& sample : samples) {
        appendSampleFrame(sampleFrameKind(topic), sample, scratch_, out_);
      }
    });
    for (const std::uint64_t writer : inbox.departed) {
      appendFrame(FrameKind::kDeparted, writer, out_);
    }
  }

  HostLink& link_;
  HostTransport& transport_;
  std::mutex mutex_;  // the middleware's thread and the loop take turns
  Inbox waiting_;     // only the loop's thread
  Inbox inbox_;
  std::vector<std::uint8_t> scratch_;
  std::vector<std::uint8_t> out_;
  Clock::time_point last_heartbeat_ = Clock::now() - kHeartbeatPeriod;
};

/// Forwards until `running` is cleared or the host is gone. With the middleware calling back,
/// the loop only keeps the heartbeat and the departures going.
void forwardToHost(Forwarder& forwarder, bool called_back, const std::atomic<bool>& running) {
  while (running.load()) {
    if (called_back) {
      std::this_thread::sleep_for(kHeartbeatPeriod);
    }
    if (!forwarder.forward(called_back ? 0.0 : 0.05)) {
      return;
    }
  }
}

std::unique_ptr<HostTransport> makeInner(const std::string& name,
                                         const HostTransportOptions& options) {
  if (name == "dds") {
    return comply::transport::makeDdsHostTransport(options);
  }
  throw comply::transport::TransportError("comply-transport runs dds, not '" + name + "'");
}

}  // namespace

int main(int argc, char** argv) {
  // The host's end (or death) closes the socket, which ends this process (serveHost returns).
  // Not PR_SET_PDEATHSIG: it follows the host's thread that started this process, and a restart
  // comes from the host's reader thread, which ends before the host has flushed.
  // Ctrl-C reaches the whole process group: the host decides when its transport ends.
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGPIPE, SIG_IGN);
#if defined(__GLIBC__)
  // What peers send lands here, a sample at a time, refused when it is over a bound. Blocks of
  // 128 kB and more are mapped and given back when freed: glibc would otherwise raise this
  // threshold to the largest block freed and keep peers' megabyte samples in its heap for good
  // (+24 MB after a run of 8 MB frame_ids; with it, back to where it started).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif

  std::map<std::string, std::string> args;
  for (int i = 1; i + 1 < argc; i += 2) {
    args[argv[i]] = argv[i + 1];
  }
  if (args.count("--fd") == 0) {
    std::fprintf(stderr,
                 "comply-transport is started by a comply host (comply run), not by hand\n");
    return 2;
  }
  HostLink link(std::atoi(args["--fd"].c_str()));
  HostTransportOptions options;
  options.name = args.count("--name") != 0 ? args["--name"] : options.name;
  options.domain_id = std::atoi(args["--domain"].c_str());
  options.network = args.count("--network") != 0 ? args["--network"] : options.network;
  options.receive_priority = std::atoi(args["--priority"].c_str());
  options.security = args["--security"];

  if (options.network == "loopback") {
    comply::transport::process::bindLoopbackOnly();
  }
  std::unique_ptr<HostTransport> transport;
  std::vector<std::uint8_t> frame;
  try {
    transport = makeInner(args["--transport"], options);
  } catch (const std::exception& error) {
    appendFrame(FrameKind::kFailed, std::string_view(error.what()), frame);
    link.send(frame);
    return 2;
  }
  appendFrame(FrameKind::kReady, std::string_view(transport->describe()), frame);
  if (!link.send(frame)) {
    return 1;
  }

  std::atomic<bool> running{true};
  Forwarder forwarder(link, *transport);
  const bool called_back = transport->notifyOnInput([&forwarder] { forwarder.forward(0.0); });
  std::thread forwarding([&] {
    // At the priority of DDS's receive threads: a command waits for neither on its way. Refused
    // (the participant said so: capabilities are given per program, so this process may have
    // less than its host), it forwards at normal priority.
    comply::makeThreadRealtime(options.receive_priority);
    forwardToHost(forwarder, called_back, running);
  });
  Outbox outbox;
  std::thread publishing([&] { publishForHost(link, *transport, outbox); });
  serveHost(link, outbox);
  // The host is gone: whatever DDS's teardown does, this process ends within 5 s.
  ::alarm(5);
  outbox.close();
  publishing.join();
  running = false;
  transport->wake();
  forwarding.join();
  transport.reset();  // its callbacks end before the forwarder they call goes
  return 0;
}
