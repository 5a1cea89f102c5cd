#pragma once
// A host transport inside one process ("in_process"): the host and its clients meet on a bus
// named like the host. No middleware, no copies beyond the messages themselves; what DDS would
// deliver, in the same order, with the same accounting on the host's side. For tests (the live
// host's tests run on it and on DDS alike) and for programs that embed a host.
//
//   auto bus = transport::InProcessBus::named("arm");   // before or after the host starts
//   bus->send(command, /*publisher=*/1);
//   bus->waitForDiagnostics(1.0, [&](const DiagnosticsMessage& d) { ... });

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "comply/transport/host_transport.hpp"

namespace comply::transport {

class InProcessBus {
 public:
  /// The bus of host `name` in this process (made on first use, shared after).
  static std::shared_ptr<InProcessBus> named(const std::string& name);

  // The clients' side. `publisher` identifies the writer (non-zero), as a DDS instance handle.
  void send(const CartesianCommandMessage& message, std::uint64_t publisher);
  /// `publisher`'s writers are gone (as a DDS writer deleted, or its process ended).
  void depart(std::uint64_t publisher);
  void send(const JointCommandMessage& message, std::uint64_t publisher);
  void send(const CartesianChunkMessage& message, std::uint64_t publisher);
  void send(const JointChunkMessage& message, std::uint64_t publisher);
  void send(const RequestMessage& message, std::uint64_t publisher);
  void send(const CommittedRequestMessage& message, std::uint64_t publisher);
  /// The newest state the host published, if any.
  [[nodiscard]] std::optional<ControllerStateMessage> state() const;
  /// Takes diagnostics as they come until `done(message)` holds or `timeout_s` passed; true when
  /// it held. Every message taken is handed to `done` once, in publication order.
  bool waitForDiagnostics(double timeout_s,
                          const std::function<bool(const DiagnosticsMessage&)>& done);
  /// The same for the answers to committed requests (every client's, as DDS delivers them).
  bool waitForCommitted(double timeout_s, const std::function<bool(const CommittedMessage&)>& done);

  // The host's side (InProcessHostTransport).
  void receive(Inbox& inbox, double timeout_s);
  void wake();
  void publish(const ControllerStateMessage& state);
  void publish(const DiagnosticsMessage& diagnostics);
  void publish(const CommittedMessage& answer);

 private:
  /// Appends `message` to one of the inbox's lists and wakes the host.
  template <typename Message>
  void post(std::vector<Sample<Message>>& list, const Message& message, std::uint64_t publisher);
  /// Hands `done` what `published` holds, in order, until it holds (see waitForDiagnostics()).
  template <typename Message>
  bool waitFor(std::deque<Message>& published, double timeout_s,
               const std::function<bool(const Message&)>& done);

  mutable std::mutex mutex_;
  std::condition_variable host_wakeup_;
  std::condition_variable client_wakeup_;
  Inbox inbox_;
  bool woken_ = false;
  std::optional<ControllerStateMessage> state_;
  std::deque<DiagnosticsMessage> diagnostics_;
  std::deque<CommittedMessage> committed_;
};

/// Registered as "in_process": the host's end of InProcessBus::named(options.name).
std::unique_ptr<HostTransport> makeInProcessHostTransport(const HostTransportOptions& options);

}  // namespace comply::transport
