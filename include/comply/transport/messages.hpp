#pragma once
// The messages of comply's live interface as C++ values, one per ROS 2 interface in msg/:
// commands (CartesianCommand, JointCommand) carry the schema's C++ command, the others mirror
// their .msg field for field. Conversion to and from the DDS types idlc generates from
// src/transport/idl/ happens inside the transport; a user of these types never sees DDS.

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "comply/core/chunk.hpp"
#include "comply/core/command_reasons.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/enum_names.hpp"
#include "comply/core/wrapper_state.hpp"
#include "comply/transport/message_tables.hpp"

namespace comply::transport {

/// builtin_interfaces/Time: seconds and nanoseconds since the epoch of the sender's clock.
struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;

  /// The first and last time a stamp holds [ns since the epoch]: int32 seconds, 1901-12-13 to
  /// 2038-01-19T03:14:07.999999999Z.
  static constexpr std::int64_t kMinNanoseconds = -(std::int64_t{1} << 31) * 1'000'000'000;
  static constexpr std::int64_t kMaxNanoseconds =
      ((std::int64_t{1} << 31) - 1) * 1'000'000'000 + 999'999'999;

  /// The wall clock (CLOCK_REALTIME), as ROS time is.
  static Stamp now() noexcept;
  /// A time outside [kMinNanoseconds, kMaxNanoseconds] saturates at the nearer end, never wraps
  /// into another time (a time 1e9 s ahead once arrived as one 3.29e9 s ago).
  static Stamp fromNanoseconds(std::int64_t nanoseconds) noexcept;
  /// `seconds` since the epoch, to the nearest nanosecond (a command's stamp_s, simulated time);
  /// saturates as fromNanoseconds() (NaN: at the first time).
  static Stamp fromSeconds(double seconds) noexcept;
  /// Whether `seconds` since the epoch is a time a stamp holds (finite, within its range).
  static bool holds(double seconds) noexcept;
  [[nodiscard]] std::int64_t nanoseconds() const noexcept;
  /// What a command's stamp_s becomes [s].
  [[nodiscard]] double seconds() const noexcept;
  friend auto operator<=>(const Stamp&, const Stamp&) = default;
};

/// A time a message may leave out (a chunk's observation and takeover, a ChunkTiming's times): all
/// zero on the wire stands for "not given", NaN in C++.
Stamp stampOrZero(double seconds) noexcept;
double secondsOrNaN(const Stamp& stamp) noexcept;

/// std_msgs/Header.
struct Header {
  Stamp stamp;
  std::string frame_id;
};

/// comply_msgs/CartesianCommand. On the wire header.stamp is the stamp; command.stamp_s is
/// derived from it when read (and ignored when written).
struct CartesianCommandMessage {
  Header header;
  CartesianCommand command;
};

/// comply_msgs/JointCommand (see CartesianCommandMessage).
struct JointCommandMessage {
  Header header;
  JointCommand command;
};

/// comply_msgs/CartesianChunk: each waypoint travels as a CartesianCommand whose header.stamp is
/// its time; chunk.waypoints[k].time_s is derived from that stamp when read, chunk.stamp_s from
/// the header's (both ignored when written, where the stamps are used).
struct CartesianChunkMessage {
  Header header;
  CartesianChunk chunk;
};

/// comply_msgs/JointChunk (see CartesianChunkMessage).
struct JointChunkMessage {
  Header header;
  JointChunk chunk;
};

/// The command and chunk message of a command type.
template <typename Command>
using CommandMessageOf = std::conditional_t<std::is_same_v<Command, CartesianCommand>,
                                            CartesianCommandMessage, JointCommandMessage>;
template <typename Command>
using ChunkMessageOf = std::conditional_t<std::is_same_v<Command, CartesianCommand>,
                                          CartesianChunkMessage, JointChunkMessage>;

/// ControllerState.STATE_*: the wrapper's state, as every host reports it.
using HostState = WrapperState;
/// ControllerState.WRENCH_SOURCE_*.
enum class WrenchSource : std::uint8_t { kNone = 0, kObserver = 1, kSensor = 2 };
inline constexpr EnumNames<WrenchSource, 3> kWrenchSourceNames{
    {{WrenchSource::kNone, "none"},
     {WrenchSource::kObserver, "observer"},
     {WrenchSource::kSensor, "sensor"}}};
std::string_view toString(WrenchSource source);
/// ControllerState.REFLEX_*: what the contact reflex did when it tripped (NONE: it has not).
enum class ReflexReaction : std::uint8_t { kNone = 0, kHold = 1, kRetreat = 2, kFault = 3 };
inline constexpr EnumNames<ReflexReaction, 4> kReflexReactionNames{
    {{ReflexReaction::kNone, "none"},
     {ReflexReaction::kHold, "hold"},
     {ReflexReaction::kRetreat, "retreat"},
     {ReflexReaction::kFault, "fault"}}};
std::string_view toString(ReflexReaction reaction);
/// ControllerState.COMMAND_KIND_*. kRequest: the request topic, which only an outcome names (a
/// controller takes Cartesian or joint commands).
enum class WireCommandKind : std::uint8_t { kCartesian = 0, kJoint = 1, kRequest = 2 };
inline constexpr EnumNames<WireCommandKind, 3> kWireCommandKindNames{
    {{WireCommandKind::kCartesian, "cartesian"},
     {WireCommandKind::kJoint, "joint"},
     {WireCommandKind::kRequest, "request"}}};
std::string_view toString(WireCommandKind kind);

/// The field types of the message tables (message_tables.hpp).
using Vector3 = std::array<double, 3>;
using Quaternion = std::array<double, 4>;  ///< x y z w
using Vector6 = std::array<double, 6>;
using Doubles = std::vector<double>;
using Strings = std::vector<std::string>;
using Counts = std::vector<std::uint64_t>;
inline constexpr Quaternion kIdentityXyzw{0.0, 0.0, 0.0, 1.0};

/// comply_msgs/ControllerState (message_tables.hpp; units in msg/ControllerState.msg). The
/// energy tank's account mirrors pipeline::PassivitySnapshot: all 0, gain_fraction 1, when off.
struct ControllerStateMessage {
  COMPLY_MESSAGE_BODY(COMPLY_CONTROLLER_STATE_FIELDS)
};

/// comply_msgs/CycleRecord: one cycle as a recording keeps it (units in msg/CycleRecord.msg).
/// The command in force is the one of the controller's kind; the other stays empty.
struct CycleRecordMessage {
  ControllerStateMessage state;
  double compute_time_s = 0.0;
  double start_lateness_s = 0.0;
  std::vector<CartesianCommandMessage> cartesian_in_force;  ///< 0 or 1 entries
  std::vector<JointCommandMessage> joint_in_force;          ///< 0 or 1 entries
};

/// CommandOutcome.OUTCOME_*.
enum class Outcome : std::uint8_t { kApplied = 0, kRejected = 1 };
inline constexpr EnumNames<Outcome, 2> kOutcomeNames{
    {{Outcome::kApplied, "applied"}, {Outcome::kRejected, "rejected"}}};
std::string_view toString(Outcome outcome);

/// CommandOutcome.REASON_*: the wrapper's rejection reasons (pipeline::RejectionReason, same
/// numbers) followed by the host's own.
enum class Reason : std::uint8_t {
  COMPLY_REJECTION_REASONS(COMPLY_REASON_ENUMERATOR)  //
  kNone = 255,
};
inline constexpr std::size_t kReasonCount = kAllRejectionReasonCount;
std::string_view toString(Reason reason);

/// A DDS GUID: 12 bytes of prefix (one per participant) and 4 of entity id.
using Gid = std::array<std::uint8_t, 16>;
/// 32 lower-case hex digits, as `ros2 topic echo` prints nothing better and logs can compare.
std::string toHex(const Gid& gid);

/// ChunkTiming.END_*: how a chunk's time in the cycle ended (pipeline::ChunkEnd, same numbers).
enum class ChunkEnd : std::uint8_t { kTookOver = 0, kSuperseded = 1, kDropped = 2 };
inline constexpr EnumNames<ChunkEnd, 3> kChunkEndNames{{{ChunkEnd::kTookOver, "took_over"},
                                                        {ChunkEnd::kSuperseded, "superseded"},
                                                        {ChunkEnd::kDropped, "dropped"}}};
std::string_view toString(ChunkEnd end);

/// comply_msgs/ChunkTiming (message_tables.hpp): a chunk's timing record (pipeline::ChunkTiming)
/// with its times on the host's clock, in its outcome and in a recording's chunk_timing channel.
struct ChunkTimingMessage {
  COMPLY_MESSAGE_BODY(COMPLY_CHUNK_TIMING_FIELDS)
};
using ChunkTimings = std::vector<ChunkTimingMessage>;

/// comply_msgs/CommandOutcome (message_tables.hpp).
struct CommandOutcomeMessage {
  COMPLY_MESSAGE_BODY(COMPLY_COMMAND_OUTCOME_FIELDS)
};
using Outcomes = std::vector<CommandOutcomeMessage>;

/// Whether `outcome` is of a command `sender` (a participant's GUID) sent: it names that sender,
/// or none (a host that cannot tell). Two senders' commands may carry the same stamp.
bool sentBy(const CommandOutcomeMessage& outcome, const Gid& sender) noexcept;

/// comply_msgs/Diagnostics (message_tables.hpp; units in msg/Diagnostics.msg).
struct DiagnosticsMessage {
  COMPLY_MESSAGE_BODY(COMPLY_DIAGNOSTICS_FIELDS)
};

/// Request.REQUEST_*.
/// kTare: the wrist force/torque sensor's reading becomes its zero (pipeline::Wrapper::tare).
/// kProbe: nothing; its outcome tells a client the host has discovered its writers. It neither
/// takes the command topics nor is refused by their publisher rule.
enum class RequestType : std::uint8_t {
  kProbe = 0,
  kActivate = 1,
  kDeactivate = 2,
  kReset = 3,
  kTare = 4
};
/// The names `comply send --request` takes.
inline constexpr EnumNames<RequestType, 5> kRequestTypeNames{
    {{RequestType::kProbe, "probe"},
     {RequestType::kActivate, "activate"},
     {RequestType::kDeactivate, "deactivate"},
     {RequestType::kReset, "reset"},
     {RequestType::kTare, "tare"}}};
std::string_view toString(RequestType request);

/// comply_msgs/Request.
struct RequestMessage {
  Header header;
  RequestType request = RequestType::kReset;
};

/// comply_msgs/CommittedRequest (message_tables.hpp): asks the host for the reference its cycles
/// will write at observation + k dt (k < count) if no new command arrives (docs/policies.md).
struct CommittedRequestMessage {
  COMPLY_MESSAGE_BODY(COMPLY_COMMITTED_REQUEST_FIELDS)
};

/// comply_msgs/Committed: the answer to one CommittedRequest (msg/Committed.msg). The reference
/// travels as the commands of the controller's kind, one per time asked for, each stamped with its
/// time: the shape of a chunk's waypoints, and every group a command carries (pose or joint
/// position, twist, the gains in force), so a policy reads it as it writes a chunk.
struct CommittedMessage {
  /// stamp: the host's clock when it answered (times before it were past); frame_id: base frame.
  Header header;
  Stamp request_stamp;  ///< the request's header.stamp
  Gid sender{};         ///< the requesting participant's GUID (all zero: not known)
  WireCommandKind command_kind = WireCommandKind::kCartesian;
  bool answered = false;  ///< false: refused, `message` says why
  /// False when a time before the running chunk could no longer be answered (those entries'
  /// position NaN).
  bool known = false;
  std::string message;                             ///< why it was refused, naming the field
  std::vector<CartesianCommandMessage> cartesian;  ///< Cartesian control: one per time
  std::vector<JointCommandMessage> joint;          ///< joint control: one per time
};

/// Whether `answer` answers the request `sender` stamped `stamp` (a host that cannot tell the
/// sender names none: then the stamp alone).
bool answers(const CommittedMessage& answer, const Stamp& stamp, const Gid& sender) noexcept;

/// The command in force as a host's `state` reports it: what a client completes a command given
/// in part from. The wire carries whole field groups, so a sender that gives a position alone must
/// send the orientation in force with it (or the group's default would be a jump); every client
/// (Python's Client, `comply send`) starts from this. Only the pose (joint position) reference is
/// in the state: other groups start from Command::zero(dof).
template <typename Command>
Command referenceInForce(const ControllerStateMessage& state, int dof) = delete;
template <>
CartesianCommand referenceInForce(const ControllerStateMessage& state, int dof);
template <>
JointCommand referenceInForce(const ControllerStateMessage& state, int dof);

/// Why a header.frame_id of `bytes` bytes is refused: "" within kMaxFrameIdBytes. `field` names
/// it ("header.frame_id", "waypoint 3: header.frame_id").
std::string frameIdRefusal(std::string_view field, std::size_t bytes);

/// A received message and who wrote it.
template <typename Message>
struct Sample {
  Message message;
  std::uint64_t publisher = 0;  ///< the writer's instance handle
  /// Non-empty when the wire held something no command may carry (a joint vector longer than
  /// kMaxDof, more waypoints than kMaxChunkWaypoints, a header.frame_id longer than
  /// kMaxFrameIdBytes): names the field. The message is then not to be used, but for its
  /// header.stamp, which the refusal's outcome names.
  std::string malformed;
  /// The sending process's participant (0: unknown): one client's command and request writers
  /// share it, so requests can be held to the publisher rule.
  std::uint64_t participant = 0;
  /// The sending participant's GUID (all zero: unknown): what the outcome names the sender by.
  Gid sender{};
  /// What a malformed sample is refused as (CommandOutcome.REASON_*).
  Reason malformed_reason = Reason::kDofMismatch;

  /// Marks the sample malformed for `reason`, unless something before already did: the first
  /// thing wrong is the one named.
  void refuse(Reason reason, std::string why) {
    if (malformed.empty()) {
      malformed = std::move(why);
      malformed_reason = reason;
    }
  }
};

}  // namespace comply::transport
