#pragma once
// The seam between a live host and its middleware: commands and requests in, state, diagnostics
// and the answers to committed requests out, as the transport-neutral messages of messages.hpp.
// DDS (the ROS 2 wire) is one implementation ("dds"), an in-process bus another ("in_process",
// for tests and for embedding a host in a program). A new middleware is one folder implementing
// HostTransport plus one line in the host's list of transports (src/host/live/transports.cpp).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a host took from its transport in one receive().
struct Inbox {
  std::vector<Sample<CartesianCommandMessage>> cartesian;
  std::vector<Sample<JointCommandMessage>> joint;
  std::vector<Sample<CartesianChunkMessage>> cartesian_chunks;
  std::vector<Sample<JointChunkMessage>> joint_chunks;
  std::vector<Sample<RequestMessage>> requests;
  /// Questions for the committed reference, answered off the cycle (publish(CommittedMessage)).
  std::vector<Sample<CommittedRequestMessage>> committed_requests;
  /// Writers that went away (deleted, or their process ended cleanly): a publisher that held the
  /// command topics releases them at once rather than after its silence times out.
  std::vector<std::uint64_t> departed;

  /// The samples of the command and chunk topics, for code that treats them alike (forEachTopic).
  auto commandTopics() { return std::tie(cartesian, joint, cartesian_chunks, joint_chunks); }
  [[nodiscard]] auto commandTopics() const {
    return std::tie(cartesian, joint, cartesian_chunks, joint_chunks);
  }
  /// The same, the requests and the committed requests: every topic a host reads.
  auto topics() { return std::tuple_cat(commandTopics(), std::tie(requests, committed_requests)); }
  [[nodiscard]] auto topics() const {
    return std::tuple_cat(commandTopics(), std::tie(requests, committed_requests));
  }

  void clear();
  [[nodiscard]] bool empty() const;
};

/// Calls visit(index, samples) for each topic's samples in a tuple of them (Inbox::topics()), in
/// the tuple's order.
template <typename Topics, typename Visit>
void forEachTopic(Topics&& topics, Visit&& visit) {
  std::apply(
      [&](auto&... samples) {
        int topic = 0;
        (visit(topic++, samples), ...);
      },
      topics);
}

inline void Inbox::clear() {
  forEachTopic(topics(), [](int /*topic*/, auto& samples) { samples.clear(); });
  departed.clear();
}

inline bool Inbox::empty() const {
  bool none = departed.empty();
  forEachTopic(topics(),
               [&](int /*topic*/, const auto& samples) { none = none && samples.empty(); });
  return none;
}

struct HostTransportOptions {
  std::string name = "comply";       ///< the host's name: topics /<name>/...
  int domain_id = 0;                 ///< DDS domain (ROS_DOMAIN_ID); others may ignore it
  std::string network = "loopback";  ///< loopback | all
  int receive_priority = 0;          ///< > 0: SCHED_FIFO priority of the receiving threads
  /// DDS Security's enclave folder (transport/participant.hpp); empty: off. Others may ignore it.
  std::filesystem::path security{};
};

class HostTransport {
 public:
  virtual ~HostTransport() = default;
  /// Waits up to `timeout_s` until input waits (or wake() is called), then appends everything
  /// waiting to `inbox`, in arrival order per topic. Every command kept until taken: none is
  /// dropped on the host's side.
  virtual void receive(Inbox& inbox, double timeout_s) = 0;
  /// Any thread: makes a receive() in progress return.
  virtual void wake() = 0;
  /// Asks the middleware to call `on_input` from its own receiving thread as soon as input waits;
  /// the caller then takes it with receive(inbox, 0). This saves the wake-up of a thread blocked
  /// in receive() (a relay such as the transport process uses it). Call once, before input is
  /// expected; false where the middleware cannot (receive() alone then).
  virtual bool notifyOnInput(const std::function<void()>& on_input) {
    (void)on_input;
    return false;
  }
  virtual void publish(const ControllerStateMessage& state) = 0;
  virtual void publish(const DiagnosticsMessage& diagnostics) = 0;
  /// The answer to a committed request (any thread but the cycle's). A middleware that carries no
  /// committed requests has none to answer: the default drops it.
  virtual void publish(const CommittedMessage& answer) { (void)answer; }
  /// Waits until the diagnostics written so far were delivered to every reader; false on timeout.
  virtual bool flush(double timeout_s) = 0;
  /// Where clients find the host, for its start-up line.
  [[nodiscard]] virtual std::string describe() const = 0;
  /// Samples the middleware received and could not read (malformed, or another type under a
  /// topic's name) since the transport started: they never reach the host, and the run's summary
  /// counts them. 0 where the middleware cannot tell.
  [[nodiscard]] virtual std::uint64_t malformedSamples() const { return 0; }
  /// Times the middleware ended (crashed, hung) and was started again since the transport
  /// started; 0 where it cannot end apart from the host (process_transport.hpp).
  [[nodiscard]] virtual std::uint64_t restarts() const { return 0; }
};

using HostTransportFactory =
    std::function<std::unique_ptr<HostTransport>(const HostTransportOptions& options)>;

/// Adds a transport under `name` (replacing one of that name).
void registerHostTransport(const std::string& name, HostTransportFactory factory);
/// The transport registered as `name`. Throws TransportError naming the registered ones when
/// there is none, or the transport's own error when it cannot start.
std::unique_ptr<HostTransport> makeHostTransport(const std::string& name,
                                                 const HostTransportOptions& options);
/// The registered names, sorted.
std::vector<std::string> hostTransportNames();

}  // namespace comply::transport
