#pragma once
// The Franka Control Interface's wire format, protocol version 7 (the robot's system 5.5, which
// libfranka 0.13.3 to 0.13.6 speak), written from its published interface description. Two
// channels:
//
//   TCP 1337   commands and their responses: a 12-byte header (command, command id, message
//              size in bytes, header included) and the command's fixed-size payload; a response
//              repeats the request's header (its size its own) and starts with a one-byte status
//   UDP        the robot's state at 1 kHz to the port the client named in Connect; the client's
//              command back to where the state came from, naming the state it answers
//
// Every number is little-endian, packed without padding. The robot's state and the client's
// command are encoded here in comply's own structures: the fields comply reads or writes by name,
// the rest kept as a block so that a message passes through unchanged.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace comply::franka::fci {

inline constexpr std::uint16_t kProtocolVersion = 7;
inline constexpr std::uint16_t kCommandPort = 1337;
inline constexpr int kJoints = 7;
inline constexpr int kErrorCount = 41;  ///< error flags in the state (franka_errors.hpp)

enum class Command : std::uint32_t {
  kConnect = 0,
  kMove = 1,
  kStopMove = 2,
  kSetCollisionBehavior = 3,
  kSetJointImpedance = 4,
  kSetCartesianImpedance = 5,
  kSetGuidingMode = 6,
  kSetEEToK = 7,
  kSetNEToEE = 8,
  kSetLoad = 9,
  kAutomaticErrorRecovery = 10,
  kLoadModelLibrary = 11,
};
inline constexpr std::uint32_t kCommandCount = 12;

/// "Connect" etc.; "unknown" past the last.
const char* commandName(Command command) noexcept;
/// The request payload's size [bytes] (header not included).
std::size_t requestPayloadBytes(Command command) noexcept;
/// The response payload's size [bytes]: the status, and Connect's version after it.
std::size_t responsePayloadBytes(Command command) noexcept;

inline constexpr std::size_t kHeaderBytes = 12;
struct Header {
  Command command = Command::kConnect;
  std::uint32_t command_id = 0;
  std::uint32_t size = 0;  ///< the whole message [bytes], header included
};
void putHeader(std::span<std::uint8_t, kHeaderBytes> out, const Header& header) noexcept;
Header getHeader(std::span<const std::uint8_t, kHeaderBytes> in) noexcept;

// Statuses: 0 is success everywhere.
enum class ConnectStatus : std::uint8_t { kSuccess = 0, kIncompatibleLibraryVersion = 1 };
/// Commands without their own statuses: StopMove's first three and AutomaticErrorRecovery's.
enum class CommandStatus : std::uint8_t {
  kSuccess = 0,
  kRejected = 1,                  ///< not possible now
  kRejectedBySafetyFunction = 2,  ///< a safety function is active
};
/// The setters (collision behaviour, impedances, frames, load, guiding mode).
enum class SetterStatus : std::uint8_t {
  kSuccess = 0,
  kRejected = 1,
  kInvalidArgument = 2,
  kRejectedBySafetyFunction = 3,
};
enum class MoveStatus : std::uint8_t {
  kSuccess = 0,  ///< the motion finished as the client asked
  kMotionStarted = 1,
  kPreempted = 2,
  kPreemptedBySafetyFunction = 3,
  kRejectedBySafetyFunction = 4,
  kRejected = 5,
  kStartAtSingularPoseRejected = 6,
  kInvalidArgumentRejected = 7,
  kReflexAborted = 8,
  kEmergencyAborted = 9,
  kInputErrorAborted = 10,
  kAborted = 11,
};
enum class RecoveryStatus : std::uint8_t {
  kSuccess = 0,
  kRejected = 1,
  kRejectedBySafetyFunction = 2,
  kManualRecoveryRequired = 3,
  kReflexAborted = 4,
  kEmergencyAborted = 5,
  kAborted = 6,
};

// Move's request.
enum class MoveController : std::uint32_t {
  kJointImpedance = 0,
  kCartesianImpedance = 1,
  kExternal = 2,  ///< the client's torques (libfranka's torque control)
};
enum class MoveGenerator : std::uint32_t {
  kJointPosition = 0,
  kJointVelocity = 1,
  kCartesianPosition = 2,
  kCartesianVelocity = 3,
  kNone = 4,
};
struct MoveRequest {
  MoveController controller = MoveController::kExternal;
  MoveGenerator generator = MoveGenerator::kJointVelocity;
  /// Translation [m], rotation [rad], elbow [rad]: how far the robot may leave the path, and
  /// its goal.
  std::array<double, 3> path_deviation{};
  std::array<double, 3> goal_deviation{};
};
inline constexpr std::size_t kMoveRequestBytes = 56;
void putMoveRequest(std::span<std::uint8_t, kMoveRequestBytes> out,
                    const MoveRequest& move) noexcept;
MoveRequest getMoveRequest(std::span<const std::uint8_t, kMoveRequestBytes> in) noexcept;

/// SetCollisionBehavior's thresholds, in the order on the wire: joint torques [N m] while
/// accelerating (lower = contact, upper = collision: a reflex), then at nominal speed; Cartesian
/// forces and torques [N, N m] the same way.
struct CollisionThresholds {
  std::array<double, 7> torque_contact_acceleration{};
  std::array<double, 7> torque_collision_acceleration{};
  std::array<double, 7> torque_contact_nominal{};
  std::array<double, 7> torque_collision_nominal{};
  std::array<double, 6> force_contact_acceleration{};
  std::array<double, 6> force_collision_acceleration{};
  std::array<double, 6> force_contact_nominal{};
  std::array<double, 6> force_collision_nominal{};
};
inline constexpr std::size_t kCollisionRequestBytes = 52 * sizeof(double);
void putCollisionThresholds(std::span<std::uint8_t, kCollisionRequestBytes> out,
                            const CollisionThresholds& thresholds) noexcept;
CollisionThresholds getCollisionThresholds(
    std::span<const std::uint8_t, kCollisionRequestBytes> in) noexcept;

// The state's modes.
enum class GeneratorMode : std::uint8_t {
  kIdle = 0,
  kJointPosition = 1,
  kJointVelocity = 2,
  kCartesianPosition = 3,
  kCartesianVelocity = 4,
  kNone = 5,
};
enum class ControllerMode : std::uint8_t {
  kJointImpedance = 0,
  kCartesianImpedance = 1,
  kExternal = 2,
  kOther = 3,
};
enum class RobotMode : std::uint8_t {
  kOther = 0,
  kIdle = 1,
  kMove = 2,
  kGuiding = 3,
  kReflex = 4,
  kUserStopped = 5,
  kAutomaticErrorRecovery = 6,
};

/// The state's arrays of doubles, in their order on the wire, each with its length in
/// stateFieldLength(). Homogeneous transforms are 4x4, column-major.
enum class StateField : std::uint8_t {
  kO_T_EE,
  kO_T_EE_d,
  kF_T_EE,
  kEE_T_K,
  kF_T_NE,
  kNE_T_EE,  // NOLINT(readability-identifier-naming)
  kM_ee,
  kI_ee,
  kF_x_Cee,
  kM_load,
  kI_load,
  kF_x_Cload,  // NOLINT(readability-identifier-naming)
  kElbow,
  kElbow_d,  // NOLINT(readability-identifier-naming)
  kTau_J,
  kTau_J_d,
  kDtau_J,
  kQ,
  kQ_d,
  kDq,
  kDq_d,
  kDdq_d,  // NOLINT(readability-identifier-naming)
  kJointContact,
  kCartesianContact,
  kJointCollision,
  kCartesianCollision,
  kTauExtHatFiltered,
  kO_F_ext_hat_K,
  kK_F_ext_hat_K,  // NOLINT(readability-identifier-naming)
  kO_dP_EE_d,
  kO_ddP_O,  // NOLINT(readability-identifier-naming)
  kElbow_c,
  kDelbow_c,
  kDdelbow_c,  // NOLINT(readability-identifier-naming)
  kO_T_EE_c,
  kO_dP_EE_c,
  kO_ddP_EE_c,  // NOLINT(readability-identifier-naming)
  kTheta,
  kDtheta,
  kCount,
};
/// The field's number of doubles.
std::size_t stateFieldLength(StateField field) noexcept;
/// Its first double's index in RobotStateMessage::values.
std::size_t stateFieldStart(StateField field) noexcept;
inline constexpr std::size_t kStateDoubles = 284;
inline constexpr std::size_t kStateBytes = 2373;

struct RobotStateMessage {
  std::uint64_t message_id = 0;  ///< the robot's time [ms], one per state
  std::array<double, kStateDoubles> values{};
  GeneratorMode generator = GeneratorMode::kIdle;
  ControllerMode controller = ControllerMode::kJointImpedance;
  std::array<bool, kErrorCount> errors{};         ///< active now
  std::array<bool, kErrorCount> reflex_reason{};  ///< what ended the last motion
  RobotMode robot_mode = RobotMode::kIdle;
  double control_command_success_rate = 0.0;  ///< of the last 100 states, answered in time

  [[nodiscard]] std::span<double> field(StateField which) noexcept {
    return std::span<double>(values).subspan(stateFieldStart(which), stateFieldLength(which));
  }
  [[nodiscard]] std::span<const double> field(StateField which) const noexcept {
    return std::span<const double>(values).subspan(stateFieldStart(which), stateFieldLength(which));
  }
};
void putRobotState(std::span<std::uint8_t, kStateBytes> out,
                   const RobotStateMessage& state) noexcept;
RobotStateMessage getRobotState(std::span<const std::uint8_t, kStateBytes> in) noexcept;

/// The client's answer to one state: a motion generator's command and the external
/// controller's torques (libfranka's torque control sends dq_c = 0 with them).
struct RobotCommandMessage {
  std::uint64_t message_id = 0;  ///< the state it answers
  std::array<double, 7> q_c{};
  std::array<double, 7> dq_c{};
  std::array<double, 16> O_T_EE_c{};  // NOLINT(readability-identifier-naming)
  std::array<double, 6> O_dP_EE_c{};  // NOLINT(readability-identifier-naming)
  std::array<double, 2> elbow_c{};
  bool valid_elbow = false;
  bool motion_finished = false;
  std::array<double, 7> tau_J_d{};  ///< [N m], on top of the robot's gravity compensation
  bool torque_finished = false;
};
inline constexpr std::size_t kCommandBytes = 371;
void putRobotCommand(std::span<std::uint8_t, kCommandBytes> out,
                     const RobotCommandMessage& command) noexcept;
RobotCommandMessage getRobotCommand(std::span<const std::uint8_t, kCommandBytes> in) noexcept;

}  // namespace comply::franka::fci
