#pragma once
// What a live host test needs from a host, whatever carries its messages: start it, read its
// state, send commands from distinct publishers, collect the outcome of every command by stamp,
// stop it. Two implementations (live_harness.cpp): "dds", `comply run` as a child process with
// this process as a DDS client (live_support.hpp), and "in_process", host::runLiveHost on a
// thread of this process over transport::InProcessBus. A test written against HostHarness runs
// on both, which is what shows that the host's behaviour does not depend on its transport.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::live_test {

class HostHarness {
 public:
  using Done = std::function<bool(const transport::DiagnosticsMessage&)>;
  using Outcomes = std::map<std::int64_t, std::vector<transport::CommandOutcomeMessage>>;

  virtual ~HostHarness() = default;

  /// Starts host `name` (config/sim/cartesian_impedance.yaml on a simulated fr3).
  virtual void start(const std::string& name) = 0;
  /// Before start(): the host records to `path` (--record) and, with `duration_s` > 0, stops by
  /// itself after that long (--duration): exactly duration_s x 1 kHz cycles.
  /// `--hardware-option` pairs for the simulated arm (e.g. wrench_offset=...), before start().
  void setHardwareOptions(std::vector<std::string> options) {
    hardware_options_ = std::move(options);
  }
  /// Before start(): the controller file instead of config/sim/cartesian_impedance.yaml.
  void setConfigFile(std::string path) { config_file_ = std::move(path); }
  void setRecording(std::string path, double duration_s) {
    record_path_ = std::move(path);
    duration_s_ = duration_s;
  }
  /// Readies publisher `publisher` (1, 2, ...: each a writer of its own) and waits until the host
  /// has accounted a no-op command of each kind from it: nothing it sends later is lost to
  /// discovery. It may take the command topics (the publisher rule). False if the host never
  /// answered.
  bool connect(int publisher, int dof);
  /// start(name), then waits up to 20 s for the first state and connects publishers 1 to
  /// `publishers` in that order (so publisher 1 takes the command topics); the first state, or
  /// none when the host sent none or did not answer a publisher's probes.
  std::optional<transport::ControllerStateMessage> startConnected(const std::string& name,
                                                                  int publishers);
  /// Sends from `publisher` (connected first); false when the transport refused the message.
  /// Safe from one thread per publisher while another thread polls.
  virtual bool send(const transport::CartesianCommandMessage& message, int publisher) = 0;
  virtual bool send(const transport::JointCommandMessage& message, int publisher) = 0;
  virtual bool send(const transport::CartesianChunkMessage& message, int publisher) = 0;
  /// After connect(): waits until the host has accounted a chunk from `publisher` (a late one,
  /// refused as late_chunk), so that no chunk it sends later is lost to discovery.
  bool connectChunks(int publisher);
  /// How the host's outcomes name `publisher` (connected first) as a command's sender.
  virtual transport::Gid sender(int publisher) = 0;
  /// Deletes `publisher`'s writers, as a sender process that exits cleanly does.
  virtual void close(int publisher) = 0;
  /// An operator request (activate, deactivate, reset) from `publisher`; false where the harness
  /// cannot send one.
  virtual bool request(transport::RequestType request, int publisher) = 0;
  /// A request as given (its header too); false where the harness cannot send one.
  virtual bool send(const transport::RequestMessage& message, int publisher) = 0;
  /// Asks the committed prefix from `publisher` (connected first) and waits up to `timeout` for
  /// the answer to it: the one that names the request's stamp and the publisher as its sender.
  virtual std::optional<transport::CommittedMessage> committed(
      const transport::CommittedRequestMessage& request, int publisher,
      std::chrono::milliseconds timeout) = 0;

  /// The newest state, waiting up to `timeout` for one.
  virtual std::optional<transport::ControllerStateMessage> state(
      std::chrono::milliseconds timeout) = 0;
  /// Reads diagnostics, recording their outcomes, until `done(last())` holds or `timeout`; true
  /// when it held.
  virtual bool poll(std::chrono::milliseconds timeout, const Done& done) = 0;
  /// Every outcome seen, by the command's stamp [ns].
  virtual Outcomes& outcomes() = 0;
  /// The newest diagnostics seen.
  [[nodiscard]] virtual const transport::DiagnosticsMessage& last() const = 0;

  /// Stops the host the way its owner would (SIGTERM to `comply run`; the stop flag, then a join)
  /// and waits for it; its exit code, or -1 when the child did not exit within 10 s.
  virtual int stop() = 0;

 protected:
  std::string record_path_;
  std::string config_file_;  ///< empty: config/sim/cartesian_impedance.yaml
  std::vector<std::string> hardware_options_;
  double duration_s_ = 0.0;
  /// Makes `publisher`'s writers and waits until they matched the host; false on timeout.
  virtual bool open(int publisher) = 0;

 private:
  template <typename Message>
  bool handshake(Message probe, int publisher);
};

/// "dds" or "in_process".
std::unique_ptr<HostHarness> makeHarness(const std::string& transport);

/// The transport-neutral tests: one instance per transport (live_harness.cpp instantiates them).
/// A test of one host on the transport its parameter names. It ends with the host stopped: an exit
/// code other than 0 fails the test.
class LiveHostOn : public ::testing::TestWithParam<std::string> {
 protected:
  void TearDown() override { EXPECT_EQ(host_->stop(), 0) << "the host did not stop cleanly"; }

  std::unique_ptr<HostHarness> host_ = makeHarness(GetParam());
};

/// The same on the in-process transport alone: for tests of the gate's rules, which one transport
/// covers, and of requests, which the DDS harness cannot send.
class LiveHostInProcess : public ::testing::Test {
 protected:
  void TearDown() override { EXPECT_EQ(host_->stop(), 0) << "the host did not stop cleanly"; }

  std::unique_ptr<HostHarness> host_ = makeHarness("in_process");
};

}  // namespace comply::live_test
