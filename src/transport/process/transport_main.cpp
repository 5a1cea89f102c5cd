// comply-transport: a live host's middleware in a process of its own (process_transport.hpp).
// The host starts it with one end of a socket pair; it runs the transport named by --transport,
// sends the host every sample it receives and a heartbeat, and publishes what the host sends.
// It ends when the host closes the socket (or dies: the kernel then signals it).
//
//   comply-transport --fd N --transport dds --name NAME --domain ID --network loopback|all
//                    --priority P

#include <sys/prctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "comply/transport/cdr.hpp"
#include "comply/transport/dds_host_transport.hpp"
#include "frames.hpp"

namespace {

using comply::transport::HostTransport;
using comply::transport::HostTransportOptions;
using comply::transport::Inbox;
using comply::transport::process::appendFrame;
using comply::transport::process::appendSampleFrame;
using comply::transport::process::Frame;
using comply::transport::process::FrameKind;
using comply::transport::process::FrameReader;

using Clock = std::chrono::steady_clock;
constexpr auto kHeartbeatPeriod = std::chrono::milliseconds(50);

/// The socket to the host, written from both threads.
class HostLink {
 public:
  explicit HostLink(int fd) : fd_(fd) {}
  /// False once the host is gone.
  bool send(const std::vector<std::uint8_t>& bytes) {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n > 0) {
        sent += static_cast<std::size_t>(n);
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else {
        return false;
      }
    }
    return true;
  }
  [[nodiscard]] int fd() const noexcept { return fd_; }

 private:
  int fd_;
  std::mutex mutex_;
};

/// The host's frames: state and diagnostics to publish, flush requests. Returns at the end of
/// the socket.
void serveHost(HostLink& link, HostTransport& transport) {
  FrameReader frames;
  std::array<std::uint8_t, 1U << 16U> buffer{};
  comply::transport::ControllerStateMessage state;
  comply::transport::DiagnosticsMessage diagnostics;
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
      if (frame->kind == FrameKind::kState && comply::transport::decodeCdr(frame->payload, state)) {
        transport.publish(state);
      } else if (frame->kind == FrameKind::kDiagnostics &&
                 comply::transport::decodeCdr(frame->payload, diagnostics)) {
        transport.publish(diagnostics);
      } else if (frame->kind == FrameKind::kFlush && frame->payload.size() == sizeof(double)) {
        double timeout_s = 0.0;
        std::memcpy(&timeout_s, frame->payload.data(), sizeof(double));
        const std::uint8_t delivered = transport.flush(timeout_s) ? 1 : 0;
        // The count first: the host's summary, printed after the flush, is then exact.
        std::vector<std::uint8_t> reply;
        appendFrame(FrameKind::kHeartbeat, transport.malformedSamples(), reply);
        appendFrame(FrameKind::kFlushed, std::span<const std::uint8_t>(&delivered, 1), reply);
        link.send(reply);
      } else {
        std::fprintf(stderr, "comply-transport: a frame from the host it cannot read (kind %d)\n",
                     static_cast<int>(frame->kind));
      }
    }
    if (frames.broken()) {
      return;
    }
  }
}

template <typename Message>
void appendSamples(FrameKind kind, const std::vector<comply::transport::Sample<Message>>& samples,
                   std::vector<std::uint8_t>& scratch, std::vector<std::uint8_t>& out) {
  for (const auto& sample : samples) {
    appendSampleFrame(kind, sample, scratch, out);
  }
}

/// What the transport receives, to the host, until `running` is cleared or the host is gone.
void forwardToHost(HostLink& link, HostTransport& transport, const std::atomic<bool>& running) {
  Inbox inbox;
  std::vector<std::uint8_t> scratch;
  std::vector<std::uint8_t> out;
  auto last_heartbeat = Clock::now() - kHeartbeatPeriod;
  while (running.load()) {
    inbox.clear();
    out.clear();
    transport.receive(inbox, 0.05);
    appendSamples(FrameKind::kCartesian, inbox.cartesian, scratch, out);
    appendSamples(FrameKind::kJoint, inbox.joint, scratch, out);
    appendSamples(FrameKind::kCartesianChunk, inbox.cartesian_chunks, scratch, out);
    appendSamples(FrameKind::kJointChunk, inbox.joint_chunks, scratch, out);
    appendSamples(FrameKind::kRequest, inbox.requests, scratch, out);
    for (const std::uint64_t writer : inbox.departed) {
      appendFrame(FrameKind::kDeparted, writer, out);
    }
    if (Clock::now() - last_heartbeat >= kHeartbeatPeriod) {
      appendFrame(FrameKind::kHeartbeat, transport.malformedSamples(), out);
      last_heartbeat = Clock::now();
    }
    if (!out.empty() && !link.send(out)) {
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
  // The host's death closes the socket; this makes sure of it even while DDS is stuck.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // Ctrl-C reaches the whole process group: the host decides when its transport ends.
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGPIPE, SIG_IGN);

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
  std::thread forwarder([&] { forwardToHost(link, *transport, running); });
  serveHost(link, *transport);
  running = false;
  transport->wake();
  forwarder.join();
  return 0;
}
