#pragma once
// comply.Client: a connection to a `comply run` host by name and DDS domain. It waits for the
// host's state (which tells the command kind and the number of joints), makes sure the host has
// discovered it (a probe command with no field group, accounted and otherwise ignored), and
// then sends commands with strictly increasing wall-clock stamps. A restarted host is found
// again by DDS discovery: the client carries on without being recreated.
//
// With `record`, what the client sends and every state and diagnostics message it takes go to an
// MCAP file (py_client_recording.hpp), the probes included (commands with no field group).
// Like the rest of the client, the recording expects one calling thread at a time.

#include <pybind11/pybind11.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "comply/transport/endpoints.hpp"
#include "py_client_recording.hpp"

namespace comply::python {

namespace py = pybind11;

class Client {
 public:
  /// `record`: the MCAP file of what the client sends and sees (none: not recorded).
  /// `security`: DDS Security's enclave folder (transport/participant.hpp; none: off).
  Client(const std::string& name, int domain, const std::string& network, double timeout_s,
         const std::optional<std::filesystem::path>& record,
         const std::optional<std::filesystem::path>& security);

  /// Schema keywords (position=..., stiffness_translational=..., task_frame=...); the stamp [ns]
  /// that identifies the command in outcome().
  std::int64_t sendCartesian(const py::kwargs& kwargs);
  std::int64_t sendJoint(const py::kwargs& kwargs);
  /// A timed chunk (chunkFromPython: a list of dicts with "time" and schema keywords), its times
  /// relative to `relative_to` [s on the host's clock: the "stamp" of the state the policy acted
  /// on], or, when None, to the host's clock now as estimated (clock()). The stamp [ns].
  std::int64_t sendChunk(const py::object& chunk, const py::object& relative_to);
  /// The host's clock as estimated from the commands' round trips (NTP's way: sent, received by
  /// the host, published, taken): offset [s] (host minus this machine), one-way latency [s], round
  /// trip [s], samples; None before any command came back.
  [[nodiscard]] py::object clock() const;
  void request(transport::RequestType request);

  /// A new state (dict of numpy arrays, with "age": seconds since it arrived), waiting up to
  /// `timeout_s` for one; None when none arrived: the host is gone or stalled.
  py::object state(double timeout_s);
  /// The newest diagnostics (dict, with "age": seconds since it arrived), when it arrived within
  /// the last `timeout_s` or arrives within `timeout_s` (the host publishes them at least once a
  /// second); None otherwise, or when their writer is gone: as state(), a stopped or stalled
  /// host is never shown by its last message.
  py::object diagnostics(double timeout_s);
  /// What became of the command sent with `stamp`: a dict, or None after `timeout_s`.
  py::object outcome(std::int64_t stamp, double timeout_s);
  /// Calls predicate(state) on every new state until it returns true (true) or `timeout_s`.
  bool waitUntil(const py::function& predicate, double timeout_s);

  [[nodiscard]] int dof() const noexcept { return dof_; }
  [[nodiscard]] bool cartesian() const noexcept { return cartesian_; }

  /// Stops the recording: the file is complete when this returns. Idempotent.
  void close();
  /// The recording's counts (written, dropped, bytes, writer_cpu_s, error), or None.
  [[nodiscard]] py::object recordingStats() const;

 private:
  /// Takes what arrived; true when a state arrived.
  bool poll(double wait_s);
  transport::Stamp nextStamp();
  void handshake(double timeout_s);
  /// Writes `message`; true when DDS took it (then it is recorded).
  template <typename Message>
  bool write(transport::Writer<Message>& writer, const Message& message);
  /// write(); throws when no host reads the topic or DDS refuses the message.
  template <typename Message>
  void publish(transport::Writer<Message>& writer, const Message& message);
  /// What a command given in part builds on: the reference in the newest state, else zero.
  template <typename Command>
  [[nodiscard]] Command referenceInForce() const;
  /// A command from keywords, stamped and published; its stamp [ns].
  template <typename Message>
  std::int64_t sendCommand(transport::Writer<Message>& writer, const py::kwargs& kwargs);

  std::string name_;
  transport::Participant participant_;
  transport::Gid sender_;  ///< participant_'s GUID: the outcomes of this client's commands name it
  transport::Writer<transport::CartesianCommandMessage> cartesian_writer_;
  transport::Writer<transport::JointCommandMessage> joint_writer_;
  transport::Writer<transport::CartesianChunkMessage> cartesian_chunk_writer_;
  transport::Writer<transport::JointChunkMessage> joint_chunk_writer_;
  transport::Writer<transport::RequestMessage> request_writer_;
  transport::Reader<transport::ControllerStateMessage> state_reader_;
  transport::Reader<transport::DiagnosticsMessage> diagnostics_reader_;
  std::optional<transport::ControllerStateMessage> state_;
  std::chrono::steady_clock::time_point state_received_;
  std::optional<transport::DiagnosticsMessage> diagnostics_;
  std::chrono::steady_clock::time_point diagnostics_received_;
  std::map<std::int64_t, transport::CommandOutcomeMessage> outcomes_;
  std::deque<std::int64_t> outcome_order_;  // oldest first, to bound outcomes_
  /// One round trip of a command: its delay (round trip less the host's time holding it) and the
  /// clock offset it implies [ns].
  struct ClockSample {
    std::int64_t delay_ns;
    std::int64_t offset_ns;
  };
  /// The round trip with the least delay among the newest, if any.
  [[nodiscard]] std::optional<ClockSample> bestClockSample() const;
  std::deque<ClockSample> clock_samples_;  // the newest kClockSamples
  std::deque<std::int64_t> awaiting_;      // stamps of the newest commands sent, not yet back
  transport::Stamp last_stamp_;
  int dof_ = 0;
  bool cartesian_ = true;
  std::unique_ptr<ClientRecording> recording_;
};

}  // namespace comply::python
