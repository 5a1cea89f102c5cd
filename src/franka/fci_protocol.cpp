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

/// Writes a message's fields into a byte span, front to back. It and Reader take the same calls,
/// so each message's layout is one list of fields (the *Fields templates below), for both ways.
class Writer {
 public:
  explicit Writer(std::uint8_t* bytes) : bytes_(bytes) {}
  template <typename Value>
  void field(const Value& value) noexcept {
    std::memcpy(bytes_ + at_, &value, sizeof(Value));
    at_ += sizeof(Value);
  }
  /// A flag byte: 1 or 0.
  void field(const bool& flag) noexcept { field(static_cast<std::uint8_t>(flag ? 1 : 0)); }
  template <typename Value, std::size_t N>
  void field(const std::array<Value, N>& values) noexcept {
    for (const Value& value : values) {
      field(value);
    }
  }
  /// An enumeration as the integer of type Wire the protocol sends it as.
  template <typename Wire, typename Enum>
  void as(const Enum& value) noexcept {
    field(static_cast<Wire>(value));
  }

 private:
  std::uint8_t* bytes_;
  std::size_t at_ = 0;
};

class Reader {
 public:
  explicit Reader(const std::uint8_t* bytes) : bytes_(bytes) {}
  template <typename Value>
  void field(Value& value) noexcept {
    std::memcpy(&value, bytes_ + at_, sizeof(Value));
    at_ += sizeof(Value);
  }
  /// A flag byte: anything but 0 is true (a bool's other bit patterns are not read as a bool).
  void field(bool& flag) noexcept {
    std::uint8_t byte = 0;
    field(byte);
    flag = byte != 0;
  }
  template <typename Value, std::size_t N>
  void field(std::array<Value, N>& values) noexcept {
    for (Value& value : values) {
      field(value);
    }
  }
  template <typename Wire, typename Enum>
  void as(Enum& value) noexcept {
    Wire wire{};
    field(wire);
    value = static_cast<Enum>(wire);
  }

 private:
  const std::uint8_t* bytes_;
  std::size_t at_ = 0;
};

// Each message's fields in wire order; `Message` is const when written.
template <typename Cursor, typename Message>
void headerFields(Cursor& cursor, Message& header) noexcept {
  cursor.template as<std::uint32_t>(header.command);
  cursor.field(header.command_id);
  cursor.field(header.size);
}

template <typename Cursor, typename Message>
void moveFields(Cursor& cursor, Message& move) noexcept {
  cursor.template as<std::uint32_t>(move.controller);
  cursor.template as<std::uint32_t>(move.generator);
  cursor.field(move.path_deviation);
  cursor.field(move.goal_deviation);
}

template <typename Cursor, typename Message>
void thresholdFields(Cursor& cursor, Message& thresholds) noexcept {
  cursor.field(thresholds.torque_contact_acceleration);
  cursor.field(thresholds.torque_collision_acceleration);
  cursor.field(thresholds.torque_contact_nominal);
  cursor.field(thresholds.torque_collision_nominal);
  cursor.field(thresholds.force_contact_acceleration);
  cursor.field(thresholds.force_collision_acceleration);
  cursor.field(thresholds.force_contact_nominal);
  cursor.field(thresholds.force_collision_nominal);
}

template <typename Cursor, typename Message>
void stateFields(Cursor& cursor, Message& state) noexcept {
  cursor.field(state.message_id);
  cursor.field(state.values);
  cursor.template as<std::uint8_t>(state.generator);
  cursor.template as<std::uint8_t>(state.controller);
  cursor.field(state.errors);
  cursor.field(state.reflex_reason);
  cursor.template as<std::uint8_t>(state.robot_mode);
  cursor.field(state.control_command_success_rate);
}

template <typename Cursor, typename Message>
void commandFields(Cursor& cursor, Message& command) noexcept {
  cursor.field(command.message_id);
  cursor.field(command.q_c);
  cursor.field(command.dq_c);
  cursor.field(command.O_T_EE_c);
  cursor.field(command.O_dP_EE_c);
  cursor.field(command.elbow_c);
  cursor.field(command.valid_elbow);
  cursor.field(command.motion_finished);
  cursor.field(command.tau_J_d);
  cursor.field(command.torque_finished);
}

/// `message` into `out` by its field list.
template <typename Message, std::size_t Bytes, typename Fields>
void encode(std::span<std::uint8_t, Bytes> out, const Message& message, Fields&& fields) noexcept {
  Writer writer(out.data());
  fields(writer, message);
}

/// The message `in` holds, by its field list.
template <typename Message, std::size_t Bytes, typename Fields>
Message decode(std::span<const std::uint8_t, Bytes> in, Fields&& fields) noexcept {
  Reader reader(in.data());
  Message message;
  fields(reader, message);
  return message;
}

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
  encode(out, header, [](auto& cursor, auto& message) { headerFields(cursor, message); });
}
Header getHeader(std::span<const std::uint8_t, kHeaderBytes> in) noexcept {
  return decode<Header>(in, [](auto& cursor, auto& message) { headerFields(cursor, message); });
}
void putMoveRequest(std::span<std::uint8_t, kMoveRequestBytes> out,
                    const MoveRequest& move) noexcept {
  encode(out, move, [](auto& cursor, auto& message) { moveFields(cursor, message); });
}
MoveRequest getMoveRequest(std::span<const std::uint8_t, kMoveRequestBytes> in) noexcept {
  return decode<MoveRequest>(in, [](auto& cursor, auto& message) { moveFields(cursor, message); });
}
void putCollisionThresholds(std::span<std::uint8_t, kCollisionRequestBytes> out,
                            const CollisionThresholds& thresholds) noexcept {
  encode(out, thresholds, [](auto& cursor, auto& message) { thresholdFields(cursor, message); });
}
CollisionThresholds getCollisionThresholds(
    std::span<const std::uint8_t, kCollisionRequestBytes> in) noexcept {
  return decode<CollisionThresholds>(
      in, [](auto& cursor, auto& message) { thresholdFields(cursor, message); });
}
std::size_t stateFieldLength(StateField field) noexcept {
  return kFieldLengths[static_cast<std::size_t>(field)];
}

std::size_t stateFieldStart(StateField field) noexcept {
  return kFieldStarts[static_cast<std::size_t>(field)];
}

void putRobotState(std::span<std::uint8_t, kStateBytes> out,
                   const RobotStateMessage& state) noexcept {
  encode(out, state, [](auto& cursor, auto& message) { stateFields(cursor, message); });
}
RobotStateMessage getRobotState(std::span<const std::uint8_t, kStateBytes> in) noexcept {
  return decode<RobotStateMessage>(
      in, [](auto& cursor, auto& message) { stateFields(cursor, message); });
}
void putRobotCommand(std::span<std::uint8_t, kCommandBytes> out,
                     const RobotCommandMessage& command) noexcept {
  encode(out, command, [](auto& cursor, auto& message) { commandFields(cursor, message); });
}
RobotCommandMessage getRobotCommand(std::span<const std::uint8_t, kCommandBytes> in) noexcept {
  return decode<RobotCommandMessage>(
      in, [](auto& cursor, auto& message) { commandFields(cursor, message); });
}
}  // namespace comply::franka::fci
