#pragma once
// The command gate: the one way a command reaches a controller, in every host (`comply run`, the
// ROS 2 controllers, Python's Sim). It accounts for every command exactly once: applied, with the
// index and wall-clock time of the cycle that took it, or rejected with a reason.
//
// A command passes, in order:
//   1. well-formed: nothing the C++ type could not hold or its bounds refuse (a joint vector
//      longer than kMaxDof, a chunk longer than kMaxChunkWaypoints, a header.frame_id longer
//      than kMaxFrameIdBytes), refused with the reason the transport names
//   2. the controller's kind (Cartesian or joint)
//   3. the publisher rule: the first sender holds the command topics until it is silent for
//      `publisher_timeout_s` (the controller's command_timeout_s, when the watchdog holds); a
//      sender is a process where the transport names it (Offer::participant: its command and
//      chunk writers are one sender), else a writer
//   4. an active controller
//   5. the stamp rules: a well-formed stamp (nanoseconds below 1e9), and not more than
//      `max_stamp_lead_s` ahead of the host's clock (a sender whose clock runs ahead, or one
//      stamp from the future, would otherwise lock every later command out as stale)
//   6. the wrapper's checks (Wrapper::submit with the exact wire stamp): strictly newer than the
//      last accepted command in integer nanoseconds (the wrapper's stamp floor, the only one; a
//      reset request clears it), finite, unit quaternions, gains, jumps, queue
// A command that passes carries the number the wrapper gave it (CommandId::sequence); the cycle
// reports the number in force after every cycle, and the gate settles every pending command up
// to it as applied: two commands are told apart however close their stamps.
//
// A chunk's outcome carries its timing record (chunk_timing.hpp) when the record came while the
// outcome was pending: the control thread notes each record (noteChunk) before the cycle
// (noteCycle), so the outcome of a chunk that took over in a cycle is settled with its record.
//
// Threads: offer() on the intake thread (any non-real-time thread), noteChunk() and noteCycle() on
// the control thread after each cycle (wait-free, no allocation), settle()/takeOutcomes() on any
// non-real-time thread. The intake and the settling share one mutex, which the control thread never
// takes.

#include <array>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "comply/core/spsc_queue.hpp"
#include "comply/pipeline/chunk_timing.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/config.hpp"

namespace comply::pipeline {

/// Why a command was refused: the wrapper's reasons (RejectionReason, same numbers) followed by the
/// gate's own (core/command_reasons.hpp). The wire's CommandOutcome.REASON_* carry these numbers.
enum class CommandReason : std::uint8_t {
  COMPLY_REJECTION_REASONS(COMPLY_REASON_ENUMERATOR)  //
  kNone = 255,
};
inline constexpr std::size_t kCommandReasonCount = kAllRejectionReasonCount;
/// The wrapper's reason as a gate reason (same number).
constexpr CommandReason commandReason(RejectionReason reason) noexcept {
  return static_cast<CommandReason>(reason);
}
std::string_view toString(CommandReason reason);

/// What an outcome accounts for: a command of either kind, or an operator request (admitRequest,
/// settleRequest). A controller takes Cartesian or joint commands.
enum class CommandKind : std::uint8_t { kCartesian = 0, kJoint = 1, kRequest = 2 };

/// Who sent a command, as every reader of the outcomes can tell: the sending participant's DDS
/// GUID (the writer's GUID prefix with the participant's entity id 0x000001c1). All zero when the
/// transport does not name it. Two senders may stamp two commands alike; the stamp and the sender
/// together name one command.
using SenderId = std::array<std::uint8_t, 16>;

/// A chunk's timing record as the control thread noted it, with the clocks of the cycle it came
/// in: its times are on the controller's clock, which hostNs() puts on the host's.
struct NotedChunk {
  ChunkTiming timing;
  std::uint64_t cycle = 0;    ///< the index of the cycle that wrote it
  double controller_s = 0.0;  ///< the controller's clock in that cycle (Controller::time())
  std::int64_t host_ns = 0;   ///< the host's clock in that cycle [ns]

  /// A time of the record on the host's clock [ns]; nullopt for NaN (not said, never).
  [[nodiscard]] std::optional<std::int64_t> hostNs(double controller_time_s) const noexcept;
};

/// What became of one command.
struct CommandOutcome {
  std::int64_t stamp_ns = 0;  ///< the command's stamp (header.stamp), exact
  /// header.stamp.nanosec as it came (Offer::nanosec): with one of 1e9 or more (invalid_stamp)
  /// the outcome names the stamp as sent, whose sum stamp_ns is, not that sum's normal form.
  std::uint32_t nanosec = 0;
  CommandKind kind = CommandKind::kCartesian;
  bool applied = false;
  CommandReason reason = CommandReason::kNone;  ///< kNone when applied
  std::uint64_t cycle = 0;                      ///< applied: the index of the cycle that took it
  std::uint64_t sequence = 0;    ///< accepted: the wrapper's number for it (CommandId::sequence)
  std::int64_t received_ns = 0;  ///< wall clock (CLOCK_REALTIME) when the gate was offered it
  std::int64_t applied_ns = 0;   ///< applied: wall clock at the end of that cycle
  std::string message;           ///< rejected: why, naming the field or the rule
  SenderId sender{};             ///< who sent it (Offer::sender)
  /// A chunk's timing record, when one came while the outcome was pending (the chunk took over,
  /// or was superseded or dropped while it waited for its takeover).
  std::optional<NotedChunk> chunk;
};

struct GateCounts {
  std::uint64_t received = 0;
  std::uint64_t applied = 0;
  std::uint64_t rejected = 0;
  std::array<std::uint64_t, kCommandReasonCount> per_reason{};
  /// The newest refusal ("" if none): a command's, the gate's or the wrapper's, named by its reason
  /// ("pose_jump: ..."), or a request's (admitRequest(), noteRefusal()).
  std::string last_rejection;
};

/// What gateOptions() reads from a controller file; built there, so the defaults are the file's.
struct GateOptions {
  CommandKind kind = CommandKind::kCartesian;  ///< the kind the controller takes
  /// Silence after which another writer may take over [s] (command_timeout_s).
  double publisher_timeout_s = defaultConfig().command_timeout_s;
  /// How far a stamp may be ahead of the host's clock [s].
  double max_stamp_lead_s = defaultConfig().validation.max_stamp_lead_s;
};

/// The gate options of a controller: its kind, the publisher timeout (command_timeout_s) and the
/// stamp lead (validation.max_stamp_lead_s) from its configuration.
GateOptions gateOptions(const WrapperConfig& config, bool cartesian);

/// One command as offered to the gate.
struct Offer {
  std::int64_t stamp_ns = 0;
  CommandKind kind = CommandKind::kCartesian;
  std::uint64_t publisher = 0;    ///< the writer's identity (a DDS instance handle, a ROS GID hash)
  std::uint64_t participant = 0;  ///< the sending process (0: unknown), for the request rule
  SenderId sender{};           ///< the sending process as the outcome names it (all zero: unknown)
  std::string_view malformed;  ///< non-empty: what the wire held that the type cannot
  /// What a malformed command is refused as (the transport's Sample::malformed_reason).
  CommandReason malformed_reason = commandReason(RejectionReason::kDofMismatch);
  std::int64_t now_ns = 0;  ///< the intake's steady clock [ns], for the publisher rule
  /// The host's clock in the stamps' timebase [ns] (wall clock for `comply run`, simulated time
  /// for Python's Sim, the node's clock under ROS 2); 0: none, no lead rule.
  std::int64_t clock_ns = 0;
  std::uint32_t nanosec = 0;  ///< header.stamp.nanosec as it came (must be below 1e9)
  bool chunk = false;         ///< a timed chunk (releasePublisher() names the last one)
};

class CommandGate {
 public:
  explicit CommandGate(GateOptions options);

  /// Passes `offer` through rules 1-5 and then `submit(offer.stamp_ns)` (rule 6, returning the
  /// wrapper's Verdict: Wrapper::submit(command, stamp_ns)), under the gate's lock; `active` says
  /// whether the controller is active. A command that passes waits until a cycle takes it
  /// (noteCycle + settle); one that fails is settled at once as rejected. Returns why it was
  /// refused, kNone when it waits for a cycle (for a host's log; the outcome, with its message,
  /// comes from takeOutcomes()).
  template <typename Submit>
  CommandReason offer(const Offer& offer, bool active, Submit&& submit);

  /// The control thread, after every cycle: `in_force` is the command in force
  /// (Controller::idInForce()). When it moved, the commands up to its number were applied by
  /// `cycle` at `time_ns()` (the host's clock [ns], asked only then: most cycles take no
  /// command). Wait-free and allocation-free; false when the event queue was full, and the same
  /// command is noted again on the next cycle.
  template <typename TimeNs>
  bool noteCycle(std::uint64_t cycle, const CommandId& in_force, TimeNs&& time_ns) noexcept {
    if (in_force.sequence == last_noted_sequence_) {
      return true;
    }
    if (!applied_.push({cycle, in_force.sequence, time_ns()})) {
      return false;
    }
    last_noted_sequence_ = in_force.sequence;
    return true;
  }

  /// The control thread, after a cycle and before its noteCycle(): a chunk's timing record of
  /// that cycle (Controller::chunks().events()), `controller_s` the controller's clock and
  /// `host_ns` the host's in that cycle. settle() gives it to the chunk's outcome if that is
  /// still pending (else it is dropped: the outcome went without it). Wait-free and
  /// allocation-free; false when the queue was full (the record is lost).
  bool noteChunk(std::uint64_t cycle, const ChunkTiming& timing, double controller_s,
                 std::int64_t host_ns) noexcept {
    return chunks_.push({timing, cycle, controller_s, host_ns});
  }

  /// Any non-real-time thread: settles the commands the noted cycles took.
  void settle();
  /// Outcomes settled since the last call, in the order they were settled.
  std::vector<CommandOutcome> takeOutcomes();
  /// At shutdown (after the last cycle): the accepted commands no cycle took, rejected as
  /// kInactive.
  void abandonPending(const std::string& why);
  /// An operator request (activate, deactivate, reset) from `participant` (the process that sent
  /// it) at steady time `now_ns`: allowed when no publisher holds the command topics, or when
  /// the holder is silent for publisher_timeout_s, or when it comes from the holder's own process.
  /// Else false with `why` set: another process may not stop the arm of the one commanding it.
  bool admitRequest(std::uint64_t participant, std::int64_t now_ns, std::string& why);
  /// What became of a request (of kind kRequest, stamped `stamp_ns`, from `sender`): carried out
  /// when `refusal` is empty, else refused for `reason` (kOtherPublisher when admitRequest()
  /// refused it; kNone when the host could not carry it out, `refusal` saying why). Settled with
  /// the commands' outcomes (takeOutcomes()), not counted among the commands; a request never
  /// takes the command topics.
  /// `nanosec`: header.stamp.nanosec as it came, so that one out of range is named as sent.
  void settleRequest(std::int64_t stamp_ns, const SenderId& sender, CommandReason reason,
                     std::string refusal, std::uint32_t nanosec = 0);
  /// `publisher`'s writers went away: if it held the command topics, the next writer may take
  /// them at once (a clean exit need not wait out publisher_timeout_s). Returns the number of the
  /// last chunk accepted from it (0: none), which the host drops if it still waits for its start
  /// (Wrapper::dropWaitingChunk): no motion starts for a sender that is gone.
  std::uint64_t releasePublisher(std::uint64_t publisher);

  /// A refusal outside the command stream (a request the host could not carry out): the newest
  /// rejection in counts() from now on. admitRequest() notes its own.
  void noteRefusal(std::string why);
  [[nodiscard]] GateCounts counts() const;
  [[nodiscard]] std::size_t pending() const;
  /// The writer that holds the command topics (0: none yet).
  [[nodiscard]] std::uint64_t publisher() const;
  [[nodiscard]] const GateOptions& options() const noexcept { return options_; }

 private:
  struct Applied {
    std::uint64_t cycle = 0;
    std::uint64_t sequence = 0;  ///< the command in force after that cycle
    std::int64_t wall_ns = 0;
  };
  struct Pending {
    std::uint64_t sequence;  ///< the number the wrapper gave it
    CommandOutcome outcome;
  };
  /// Rules 1-5: kNone when they pass, else the reason (and the outcome settled as rejected).
  CommandReason admitLocked(const Offer& offer, bool active, CommandOutcome& outcome);
  /// Settles `outcome` as rejected for `reason`; returns `reason`.
  CommandReason rejectLocked(CommandOutcome& outcome, CommandReason reason, std::string message);
  void acceptLocked(std::uint64_t sequence, CommandOutcome& outcome);
  /// Gives the noted timing records to the pending outcomes of their chunks.
  void attachChunksLocked();

  GateOptions options_;
  mutable std::mutex mutex_;
  GateCounts counts_;
  std::uint64_t holder_ = 0;
  std::uint64_t holder_participant_ = 0;
  std::int64_t holder_heard_ns_ = 0;
  std::uint64_t chunk_publisher_ = 0;  // who sent the last accepted chunk, and its number
  std::uint64_t chunk_sequence_ = 0;
  std::deque<Pending> pending_;
  std::vector<CommandOutcome> settled_;
  // The control thread's side.
  SpscQueue<Applied> applied_{4096};
  SpscQueue<NotedChunk> chunks_{256};
  std::uint64_t last_noted_sequence_ = 0;
};

template <typename Submit>
CommandReason CommandGate::offer(const Offer& offer, bool active, Submit&& submit) {
  const std::lock_guard<std::mutex> lock(mutex_);
  CommandOutcome outcome;
  if (const CommandReason refused = admitLocked(offer, active, outcome);
      refused != CommandReason::kNone) {
    return refused;
  }
  const Verdict verdict = submit(offer.stamp_ns);
  if (!verdict.accepted) {
    return rejectLocked(outcome, commandReason(verdict.reason), verdict.message);
  }
  acceptLocked(verdict.sequence, outcome);
  if (offer.chunk) {
    chunk_publisher_ = offer.publisher;
    chunk_sequence_ = verdict.sequence;
  }
  return CommandReason::kNone;
}

}  // namespace comply::pipeline
