#pragma once
// comply.Client: a connection to a `comply run` host by name and DDS domain. It waits for the
// host's state (which tells the command kind and the number of joints), makes sure the host has
// discovered its writers (a probe request, which the host accounts and otherwise ignores), and
// then sends commands with strictly increasing wall-clock stamps. A restarted host is found
// again by DDS discovery: the client carries on without being recreated.
//
// Only a command or a chunk makes a client the publisher that holds the host's command topics:
// the probe is a request, and requests never take the topics, so a client that only reads the
// state and diagnostics (a dashboard) locks no sender out. close() deletes the client's DDS
// participant: its writers go with it, and the host lets go of the topics at once.
//
// Threads: every method may be called from any thread, also at the same time (a policy that reads
// the state on one thread and sends on another). Three locks, never taken in another order:
//   sending_   stamping and writing, so that stamps leave in the order they were taken
//   reading_   the DDS readers: one thread at a time waits on and takes from them; the others
//              wait for it to deliver (arrived_) rather than queue for the readers
//   data_      what arrived (state, diagnostics, outcomes, answers to committed requests, the
//              clock's round trips) and the recording (one lane: one writer at a time)
// The holders of sending_ and reading_ wait on DDS, so those two are taken with the GIL released;
// no holder of data_ waits for anything, so it may be taken with the GIL held.
//
// With `record`, what the client sends and every state and diagnostics message it takes go to an
// MCAP file (py_client_recording.hpp), the probes included.

#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
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
  std::int64_t sendChunk(const py::object& chunk, const py::object& relative_to,
                         const py::object& keep);
  /// The host's clock as estimated from the commands' round trips (NTP's way: sent, received by
  /// the host, published, taken): offset [s] (host minus this machine), one-way latency [s], round
  /// trip [s], samples; None before any command came back.
  [[nodiscard]] py::object clock() const;
  /// Sends `request`; its stamp [ns], which names its outcome in outcome().
  std::int64_t request(transport::RequestType request);
  /// The reference the host's cycles will write at observation_time + k dt (k < n, the host's
  /// clock) if no new command arrives: one request on /<name>/committed_request, its own answer
  /// waited for up to `timeout_s` (py_client_committed.cpp). The same dict as Sim.committed().
  /// Raises ValueError when the host refused the request (its words), TimeoutError without answer.
  py::dict committed(double observation_time_s, double dt_s, int count, double timeout_s);

  /// A new state (dict of numpy arrays, with "age": seconds since it arrived), waiting up to
  /// `timeout_s` for one; None when none arrived: the host is gone or stalled.
  py::object state(double timeout_s);
  /// The newest diagnostics (dict, with "age": seconds since it arrived), when it arrived within
  /// the last `timeout_s` or arrives within `timeout_s` (the host publishes them at least once a
  /// second); None otherwise, or when their writer is gone: as state(), a stopped or stalled
  /// host is never shown by its last message.
  py::object diagnostics(double timeout_s);
  /// What became of the command or request sent with `stamp`: a dict, or None after `timeout_s`.
  py::object outcome(std::int64_t stamp, double timeout_s);
  /// Calls predicate(state) on every new state until it returns true (true) or `timeout_s`.
  bool waitUntil(const py::function& predicate, double timeout_s);

  [[nodiscard]] int dof() const noexcept { return dof_; }
  [[nodiscard]] bool cartesian() const noexcept { return cartesian_; }

  /// Deletes the DDS participant (the host sees the writers go and releases the command topics
  /// at once) and stops the recording: the file is complete when this returns. Idempotent; any
  /// other call but recordingStats() raises afterwards.
  void close();
  /// The recording's counts (written, dropped, bytes, writer_cpu_s, error), or None.
  [[nodiscard]] py::object recordingStats() const;

 private:
  /// The DDS side, gone after close(). The command and chunk writers come before the request
  /// writer: a host discovers a participant's writers in the order they were made, so the one
  /// that has accounted a request from it knows them all.
  struct Link {
    Link(const transport::ParticipantOptions& options, const std::string& name);
    transport::Participant participant;
    // A sender faster than the host waits for room instead of losing its oldest command.
    transport::Writer<transport::CartesianCommandMessage> cartesian;
    transport::Writer<transport::JointCommandMessage> joint;
    transport::Writer<transport::CartesianChunkMessage> cartesian_chunk;
    transport::Writer<transport::JointChunkMessage> joint_chunk;
    transport::Writer<transport::CommittedRequestMessage> committed_request;
    transport::Writer<transport::RequestMessage> request;
    transport::Reader<transport::ControllerStateMessage> state;
    transport::Reader<transport::DiagnosticsMessage> diagnostics;
    transport::Reader<transport::CommittedMessage> committed;
    /// A state or an answer to a committed request waits: what a poll waits for.
    transport::WaitSet arrivals;
  };
  /// One round trip of a command: its delay (round trip less the host's time holding it) and the
  /// clock offset it implies [ns].
  struct ClockSample {
    std::int64_t delay_ns;
    std::int64_t offset_ns;
  };

  // Receiving (py_client_receive.cpp).
  /// Takes what arrives until done() (called under data_) holds, or `timeout_s` (after one look
  /// at least); whether it held. The thread that finds the readers free reads them, waiting up to
  /// `step_s` at a time; the others wait for what it delivers. The GIL must be released.
  bool receiveUntil(const std::function<bool()>& done, double timeout_s, double step_s);
  /// Under reading_: waits up to `wait_s` for a state, takes what arrived; then wakes arrived_.
  void pollLocked(double wait_s);
  /// Under data_: this client's outcomes among `diagnostics`, timing its own round trips.
  void takeOutcomes(transport::DiagnosticsMessage& diagnostics, std::int64_t taken_ns);
  /// Under data_: this client's answers among `answers` (every client's), kept by stamp.
  void takeAnswers(std::vector<transport::Sample<transport::CommittedMessage>>& answers);
  /// The round trip with the least delay among the newest, if any (under data_).
  [[nodiscard]] std::optional<ClockSample> bestClockSample() const;
  /// Raises when close() was called (under data_).
  void checkOpen() const;

  // Sending (py_client.cpp). Each runs under sending_, the GIL released.
  /// Sends probe requests until the host accounts one: it has then discovered every writer.
  void handshake(double timeout_s);
  transport::Stamp nextStamp();
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
  std::int64_t sendCommand(transport::Writer<Message> Link::*writer, const py::kwargs& kwargs);
  /// The link, under sending_ or reading_; raises when closed.
  Link& link() const;

  const std::string name_;
  int dof_ = 0;
  bool cartesian_ = true;
  transport::Gid sender_{};  ///< the participant's GUID: the outcomes of this client name it

  mutable std::mutex sending_;
  transport::Stamp last_stamp_;  // sending_

  mutable std::mutex reading_;
  std::unique_ptr<Link> link_;  // deleted under sending_ and reading_ both

  mutable std::mutex data_;
  std::condition_variable arrived_;  // a poll ended (with or without news), or close()
  bool closed_ = false;
  std::optional<transport::ControllerStateMessage> state_;
  std::uint64_t states_taken_ = 0;  // tells a new state from the one a caller saw before
  bool host_matched_ = false;       // a host's state writer matched at the last poll
  std::chrono::steady_clock::time_point state_received_;
  std::optional<transport::DiagnosticsMessage> diagnostics_;
  std::chrono::steady_clock::time_point diagnostics_received_;
  std::map<std::int64_t, transport::CommandOutcomeMessage> outcomes_;
  std::deque<std::int64_t> outcome_order_;  // oldest first, to bound outcomes_
  std::deque<ClockSample> clock_samples_;   // the newest kClockSamples
  std::deque<std::int64_t> awaiting_;       // stamps of the newest commands sent, not yet back
  std::map<std::int64_t, transport::CommittedMessage> answers_;  // to committed(), by stamp
  std::deque<std::int64_t> answer_order_;                        // oldest first, to bound them
  std::unique_ptr<ClientRecording> recording_;
};

}  // namespace comply::python
