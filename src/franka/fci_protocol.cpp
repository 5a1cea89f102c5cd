// The FCI's messages to and from bytes (fci_protocol.hpp).

#include "comply/franka/fci_protocol.hpp"

#include <bit>
#include <cstring>

namespace comply::franka::fci {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the FCI's numbers are little-endian and are copied as they are");

constexpr std::array<std::uint8_t, static_cast<std::size_t>(StateField::kCount)> kFieldLengths{
    16, 16, 16, 16, 16, 16,        // O_T_EE .. NE_T_EE
    1,  9,  3,  1,  9,  3,         // m_ee, I_ee, F_x_Cee, m_load, I_load, F_x_Cload
    2,  2,                         // elbow, elbow_d
    7,  7,  7,  7,  7,  7,  7, 7,  // tau_J .. ddq_d
    7,  6,  7,  6,                 // contact and collision flags
    7,  6,  6,                     // external torque and wrench estimates
    6,  3,                         // O_dP_EE_d, O_ddP_O
    2,  2,  2,                     // elbow_c, delbow_c, ddelbow_c
    16, 6,  6,                     // O_T_EE_c, O_dP_EE_c, O_ddP_EE_c
    7,  7,                         // theta, dtheta
};

constexpr std::array<std::size_t, kFieldLengths.size() + 1> fieldStarts() {
  std::array<std::size_t, kFieldLengths.size() + 1> starts{};
  for (std::size_t i = 0; i < kFieldLengths.size(); ++i) {
    starts[i + 1] = starts[i] + kFieldLengths[i];
  }
  return starts;
}
constexpr auto kFieldStarts = fieldStarts();
static_assert(kFieldStarts.back() == kStateDoubles);
static_assert(8 + 8 * kStateDoubles + 2 + 2 * std::size_t{kErrorCount} + 1 + 8 == kStateBytes);
static_assert(8 + sizeof(double) * (7 + 7 + 16 + 6 + 2) + 2 + sizeof(double) * 7 + 1 ==
              kCommandBytes);

/// Copies in and out of a byte span, front to back.
class Cursor {
 public:
  explicit Cursor(std::uint8_t* bytes) : bytes_(bytes) {}
  template <typename Value>
  void put(const Value& value) noexcept {
    std::memcpy(bytes_ + at_, &value, sizeof(Value));
    at_ += sizeof(Value);
  }
  template <typename Value, std::size_t N>
  void putAll(const std::array<Value, N>& values) noexcept {
    for (const Value& value : values) {
      put(value);
    }
  }
  [[nodiscard]] std::size_t at() const noexcept { return at_; }

 private:
  std::uint8_t* bytes_;
  std::size_t at_ = 0;
};

class ReadCursor {
 public:
  explicit ReadCursor(const std::uint8_t* bytes) : bytes_(bytes) {}
  template <typename Value>
  void get(Value& value) noexcept {
    std::memcpy(&value, bytes_ + at_, sizeof(Value));
    at_ += sizeof(Value);
  }
  template <typename Value, std::size_t N>
  void getAll(std::array<Value, N>& values) noexcept {
    for (Value& value : values) {
      get(value);
    }
  }
  /// A flag byte: anything but 0 is true (a bool's other bit patterns are not read as a bool).
  void getFlag(bool& flag) noexcept {
    std::uint8_t byte = 0;
    get(byte);
    flag = byte != 0;
  }
  template <std::size_t N>
  void getFlags(std::array<bool, N>& flags) noexcept {
    for (bool& flag : flags) {
      getFlag(flag);
    }
  }

 private:
  const std::uint8_t* bytes_;
  std::size_t at_ = 0;
};

}  // namespace

const char* commandName(Command command) noexcept {
  static constexpr std::array<const char*, kCommandCount> kNames{"Connect",
                                                                 "Move",
                                                                 "StopMove",
                                                                 "SetCollisionBehavior",
                                                                 "SetJointImpedance",
                                                                 "SetCartesianImpedance",
                                                                 "SetGuidingMode",
                                                                 "SetEEToK",
                                                                 "SetNEToEE",
                                                                 "SetLoad",
                                                                 "AutomaticErrorRecovery",
                                                                 "LoadModelLibrary"};
  const auto index = static_cast<std::uint32_t>(command);
  return index < kCommandCount ? kNames[index] : "unknown";
}

std::size_t requestPayloadBytes(Command command) noexcept {
  switch (command) {
    case Command::kConnect:
      return 4;  // version, UDP port
    case Command::kMove:
      return kMoveRequestBytes;
    case Command::kStopMove:
    case Command::kAutomaticErrorRecovery:
      return 0;
    case Command::kSetCollisionBehavior:
      return kCollisionRequestBytes;
    case Command::kSetJointImpedance:
      return 7 * sizeof(double);
    case Command::kSetCartesianImpedance:
      return 6 * sizeof(double);
    case Command::kSetGuidingMode:
      return 7;  // six axes and the nullspace, one byte each
    case Command::kSetEEToK:
    case Command::kSetNEToEE:
      return 16 * sizeof(double);
    case Command::kSetLoad:
      return 13 * sizeof(double);  // mass, centre of mass, inertia
    case Command::kLoadModelLibrary:
      return 2;  // architecture, operating system
  }
  return 0;
}

std::size_t responsePayloadBytes(Command command) noexcept {
  return command == Command::kConnect ? 3 : 1;
}

void putHeader(std::span<std::uint8_t, kHeaderBytes> out, const Header& header) noexcept {
  Cursor cursor(out.data());
  cursor.put(static_cast<std::uint32_t>(header.command));
  cursor.put(header.command_id);
  cursor.put(header.size);
}

Header getHeader(std::span<const std::uint8_t, kHeaderBytes> in) noexcept {
  ReadCursor cursor(in.data());
  std::uint32_t command = 0;
  Header header;
  cursor.get(command);
  cursor.get(header.command_id);
  cursor.get(header.size);
  header.command = static_cast<Command>(command);
  return header;
}

void putMoveRequest(std::span<std::uint8_t, kMoveRequestBytes> out,
                    const MoveRequest& move) noexcept {
  Cursor cursor(out.data());
  cursor.put(static_cast<std::uint32_t>(move.controller));
  cursor.put(static_cast<std::uint32_t>(move.generator));
  cursor.putAll(move.path_deviation);
  cursor.putAll(move.goal_deviation);
}

MoveRequest getMoveRequest(std::span<const std::uint8_t, kMoveRequestBytes> in) noexcept {
  ReadCursor cursor(in.data());
  std::uint32_t controller = 0;
  std::uint32_t generator = 0;
  MoveRequest move;
  cursor.get(controller);
  cursor.get(generator);
  cursor.getAll(move.path_deviation);
  cursor.getAll(move.goal_deviation);
  move.controller = static_cast<MoveController>(controller);
  move.generator = static_cast<MoveGenerator>(generator);
  return move;
}

void putCollisionThresholds(std::span<std::uint8_t, kCollisionRequestBytes> out,
                            const CollisionThresholds& thresholds) noexcept {
  Cursor cursor(out.data());
  cursor.putAll(thresholds.torque_contact_acceleration);
  cursor.putAll(thresholds.torque_collision_acceleration);
  cursor.putAll(thresholds.torque_contact_nominal);
  cursor.putAll(thresholds.torque_collision_nominal);
  cursor.putAll(thresholds.force_contact_acceleration);
  cursor.putAll(thresholds.force_collision_acceleration);
  cursor.putAll(thresholds.force_contact_nominal);
  cursor.putAll(thresholds.force_collision_nominal);
}

CollisionThresholds getCollisionThresholds(
    std::span<const std::uint8_t, kCollisionRequestBytes> in) noexcept {
  ReadCursor cursor(in.data());
  CollisionThresholds thresholds;
  cursor.getAll(thresholds.torque_contact_acceleration);
  cursor.getAll(thresholds.torque_collision_acceleration);
  cursor.getAll(thresholds.torque_contact_nominal);
  cursor.getAll(thresholds.torque_collision_nominal);
  cursor.getAll(thresholds.force_contact_acceleration);
  cursor.getAll(thresholds.force_collision_acceleration);
  cursor.getAll(thresholds.force_contact_nominal);
  cursor.getAll(thresholds.force_collision_nominal);
  return thresholds;
}

std::size_t stateFieldLength(StateField field) noexcept {
  return kFieldLengths[static_cast<std::size_t>(field)];
}

std::size_t stateFieldStart(StateField field) noexcept {
  return kFieldStarts[static_cast<std::size_t>(field)];
}

void putRobotState(std::span<std::uint8_t, kStateBytes> out,
                   const RobotStateMessage& state) noexcept {
  Cursor cursor(out.data());
  cursor.put(state.message_id);
  cursor.putAll(state.values);
  cursor.put(static_cast<std::uint8_t>(state.generator));
  cursor.put(static_cast<std::uint8_t>(state.controller));
  for (const bool flag : state.errors) {
    cursor.put(static_cast<std::uint8_t>(flag ? 1 : 0));
  }
  for (const bool flag : state.reflex_reason) {
    cursor.put(static_cast<std::uint8_t>(flag ? 1 : 0));
  }
  cursor.put(static_cast<std::uint8_t>(state.robot_mode));
  cursor.put(state.control_command_success_rate);
}

RobotStateMessage getRobotState(std::span<const std::uint8_t, kStateBytes> in) noexcept {
  ReadCursor cursor(in.data());
  RobotStateMessage state;
  cursor.get(state.message_id);
  cursor.getAll(state.values);
  std::uint8_t generator = 0;
  std::uint8_t controller = 0;
  std::uint8_t robot_mode = 0;
  cursor.get(generator);
  cursor.get(controller);
  cursor.getFlags(state.errors);
  cursor.getFlags(state.reflex_reason);
  cursor.get(robot_mode);
  cursor.get(state.control_command_success_rate);
  state.generator = static_cast<GeneratorMode>(generator);
  state.controller = static_cast<ControllerMode>(controller);
  state.robot_mode = static_cast<RobotMode>(robot_mode);
  return state;
}

void putRobotCommand(std::span<std::uint8_t, kCommandBytes> out,
                     const RobotCommandMessage& command) noexcept {
  Cursor cursor(out.data());
  cursor.put(command.message_id);
  cursor.putAll(command.q_c);
  cursor.putAll(command.dq_c);
  cursor.putAll(command.O_T_EE_c);
  cursor.putAll(command.O_dP_EE_c);
  cursor.putAll(command.elbow_c);
  cursor.put(static_cast<std::uint8_t>(command.valid_elbow ? 1 : 0));
  cursor.put(static_cast<std::uint8_t>(command.motion_finished ? 1 : 0));
  cursor.putAll(command.tau_J_d);
  cursor.put(static_cast<std::uint8_t>(command.torque_finished ? 1 : 0));
}

RobotCommandMessage getRobotCommand(std::span<const std::uint8_t, kCommandBytes> in) noexcept {
  ReadCursor cursor(in.data());
  RobotCommandMessage command;
  cursor.get(command.message_id);
  cursor.getAll(command.q_c);
  cursor.getAll(command.dq_c);
  cursor.getAll(command.O_T_EE_c);
  cursor.getAll(command.O_dP_EE_c);
  cursor.getAll(command.elbow_c);
  cursor.getFlag(command.valid_elbow);
  cursor.getFlag(command.motion_finished);
  cursor.getAll(command.tau_J_d);
  cursor.getFlag(command.torque_finished);
  return command;
}

}  // namespace comply::franka::fci
