// The host's side of a transport in its own process (see process_transport.hpp): the
// HostTransport the host sees, over the process's supervisor (supervisor.hpp) and the frames it
// exchanges with the process (frame_adapter.hpp).

#include "comply/transport/process_transport.hpp"

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "comply/core/install_paths.hpp"
#include "frame_adapter.hpp"
#include "supervisor.hpp"

namespace comply::transport {
namespace {

using Clock = std::chrono::steady_clock;
using process::FrameKind;

class ProcessHostTransport final : public HostTransport {
 public:
  ProcessHostTransport(HostTransportOptions options, ProcessTransportOptions process)
      : child_(std::move(options), std::move(process)) {
    // The first start is waited for: an error of the inner transport is the host's start-up error.
    Inbox held;
    child_.startAndWait(held, pending_.departed);
    pending_ = std::move(held);
  }

  void receive(Inbox& inbox, double timeout_s) override {
    const std::lock_guard<std::mutex> lock(read_mutex_);
    appendPending(inbox);
    if (!child_.running()) {
      // Down: wait for the restart time (or a wake), then start it again.
      child_.restartWhenDue(timeout_s);
      return;
    }
    child_.watch(inbox, pending_.departed, timeout_s, /*report=*/true);
  }

  void wake() override { child_.wake(); }

  void publish(const ControllerStateMessage& state) override {
    sendEncoded(FrameKind::kState, state);
  }

  void publish(const DiagnosticsMessage& diagnostics) override {
    sendEncoded(FrameKind::kDiagnostics, diagnostics);
  }

  void publish(const CommittedMessage& answer) override {
    sendEncoded(FrameKind::kCommitted, answer);
  }

  bool flush(double timeout_s) override {
    const std::lock_guard<std::mutex> lock(read_mutex_);
    child_.frames().expectFlushed();
    if (!child_.send([&] { return process::OutgoingFrames::flushRequest(timeout_s); })) {
      return false;
    }
    // The answer comes after the process's own wait, plus the hop back.
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s + 0.5);
    while (!child_.frames().flushed() && child_.running() && Clock::now() < deadline) {
      child_.watch(pending_, pending_.departed, 0.05, /*report=*/true);
    }
    return child_.frames().flushed().value_or(false);
  }

  [[nodiscard]] std::string describe() const override {
    return child_.frames().description() + " in its own process (" + child_.program().string() +
           ")";
  }

  [[nodiscard]] std::uint64_t malformedSamples() const override {
    return child_.frames().malformedSamples();
  }
  [[nodiscard]] std::uint64_t restarts() const override { return child_.restarts(); }

 private:
  /// `message` in one frame of `kind` to the process.
  template <typename Message>
  void sendEncoded(FrameKind kind, const Message& message) {
    child_.send([&]() -> const std::vector<std::uint8_t>& { return out_.encode(kind, message); });
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
    move_all(pending_.committed_requests, inbox.committed_requests);
    move_all(pending_.departed, inbox.departed);
  }

  process::ProcessSupervisor child_;
  std::mutex read_mutex_;  ///< the reading side: receive, flush
  Inbox pending_;  ///< taken outside receive() (start-up, flush, an ended process's writers)
  process::OutgoingFrames out_;  ///< under child_'s send lock
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
