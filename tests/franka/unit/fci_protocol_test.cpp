// The FCI's messages (fci_protocol.hpp): sizes and byte offsets as the protocol's description
// gives them, counted here by hand, and every field back as it went in.

#include "comply/franka/fci_protocol.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace comply::franka::fci {
namespace {

double doubleAt(std::span<const std::uint8_t> bytes, std::size_t offset) {
  double value = 0.0;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

TEST(FciProtocol, StateFieldsSitWhereTheDescriptionPutsThem) {
  // Counted from the description: 6 transforms (96), m_ee, I_ee, F_x_Cee, m_load, I_load,
  // F_x_Cload (26), elbow and elbow_d (4), tau_J, tau_J_d, dtau_J (21): q is double 147.
  EXPECT_EQ(stateFieldStart(StateField::kQ), 147U);
  EXPECT_EQ(stateFieldStart(StateField::kTau_J), 126U);
  EXPECT_EQ(stateFieldStart(StateField::kO_F_ext_hat_K), 215U);
  EXPECT_EQ(stateFieldStart(StateField::kDtheta), 277U);
  EXPECT_EQ(stateFieldLength(StateField::kO_T_EE), 16U);
  EXPECT_EQ(stateFieldLength(StateField::kO_ddP_O), 3U);

  RobotStateMessage state;
  state.message_id = 0x0102030405060708ULL;
  for (std::size_t i = 0; i < state.values.size(); ++i) {
    state.values[i] = 0.5 * static_cast<double>(i) - 3.0;
  }
  state.generator = GeneratorMode::kJointVelocity;
  state.controller = ControllerMode::kExternal;
  state.errors[25] = true;
  state.reflex_reason[6] = true;
  state.robot_mode = RobotMode::kReflex;
  state.control_command_success_rate = 0.93;
  std::array<std::uint8_t, kStateBytes> bytes{};
  putRobotState(bytes, state);

  EXPECT_EQ(bytes[0], 0x08);  // little-endian
  EXPECT_EQ(bytes[7], 0x01);
  EXPECT_EQ(doubleAt(bytes, 8 + 8 * 147), state.field(StateField::kQ)[0]);
  const std::size_t flags_at = 8 + 8 * kStateDoubles;
  EXPECT_EQ(bytes[flags_at], 2);      // generator: joint velocity
  EXPECT_EQ(bytes[flags_at + 1], 2);  // controller: external
  EXPECT_EQ(bytes[flags_at + 2 + 25], 1);
  EXPECT_EQ(bytes[flags_at + 2 + 41 + 6], 1);
  EXPECT_EQ(bytes[flags_at + 2 + 82], 4);  // robot mode: reflex
  EXPECT_EQ(doubleAt(bytes, kStateBytes - 8), 0.93);

  const RobotStateMessage back = getRobotState(bytes);
  EXPECT_EQ(back.message_id, state.message_id);
  EXPECT_EQ(back.values, state.values);
  EXPECT_EQ(back.generator, state.generator);
  EXPECT_EQ(back.controller, state.controller);
  EXPECT_EQ(back.errors, state.errors);
  EXPECT_EQ(back.reflex_reason, state.reflex_reason);
  EXPECT_EQ(back.robot_mode, state.robot_mode);
  EXPECT_EQ(back.control_command_success_rate, state.control_command_success_rate);
}

TEST(FciProtocol, CommandCarriesTheTorquesAfterTheMotion) {
  RobotCommandMessage command;
  command.message_id = 77;
  command.dq_c.fill(0.0);
  command.q_c[6] = 1.25;
  command.motion_finished = true;
  for (std::size_t j = 0; j < 7; ++j) {
    command.tau_J_d[j] = static_cast<double>(j) + 0.5;
  }
  command.torque_finished = true;
  std::array<std::uint8_t, kCommandBytes> bytes{};
  putRobotCommand(bytes, command);
  // message id (8), q_c, dq_c, O_T_EE_c, O_dP_EE_c, elbow_c (38 doubles), two flags.
  EXPECT_EQ(doubleAt(bytes, 8 + 6 * 8), 1.25);
  EXPECT_EQ(bytes[8 + 38 * 8], 0);      // valid_elbow
  EXPECT_EQ(bytes[8 + 38 * 8 + 1], 1);  // motion finished
  EXPECT_EQ(doubleAt(bytes, 8 + 38 * 8 + 2), 0.5);
  EXPECT_EQ(doubleAt(bytes, 8 + 38 * 8 + 2 + 6 * 8), 6.5);
  EXPECT_EQ(bytes[kCommandBytes - 1], 1);

  const RobotCommandMessage back = getRobotCommand(bytes);
  EXPECT_EQ(back.message_id, 77U);
  EXPECT_EQ(back.q_c, command.q_c);
  EXPECT_EQ(back.tau_J_d, command.tau_J_d);
  EXPECT_TRUE(back.motion_finished);
  EXPECT_FALSE(back.valid_elbow);
  EXPECT_TRUE(back.torque_finished);
}

TEST(FciProtocol, RequestsHaveTheirSizesAndOrder) {
  EXPECT_EQ(requestPayloadBytes(Command::kConnect), 4U);
  EXPECT_EQ(requestPayloadBytes(Command::kMove), 56U);
  EXPECT_EQ(requestPayloadBytes(Command::kStopMove), 0U);
  EXPECT_EQ(requestPayloadBytes(Command::kSetCollisionBehavior), 416U);
  EXPECT_EQ(requestPayloadBytes(Command::kSetLoad), 104U);
  EXPECT_EQ(responsePayloadBytes(Command::kConnect), 3U);
  EXPECT_EQ(responsePayloadBytes(Command::kMove), 1U);
  EXPECT_STREQ(commandName(Command::kAutomaticErrorRecovery), "AutomaticErrorRecovery");
  EXPECT_STREQ(commandName(static_cast<Command>(99)), "unknown");

  std::array<std::uint8_t, kHeaderBytes> header{};
  putHeader(header, {Command::kSetCollisionBehavior, 9, 428});
  EXPECT_EQ(header[0], 3);
  EXPECT_EQ(header[4], 9);
  EXPECT_EQ(header[8], 428 & 0xff);
  EXPECT_EQ(header[9], 428 >> 8);
  const Header back = getHeader(header);
  EXPECT_EQ(back.command, Command::kSetCollisionBehavior);
  EXPECT_EQ(back.command_id, 9U);
  EXPECT_EQ(back.size, 428U);

  MoveRequest move;
  move.controller = MoveController::kExternal;
  move.generator = MoveGenerator::kJointVelocity;
  move.path_deviation = {10.0, 3.12, 2.0};
  move.goal_deviation = {1.0, 2.0, 3.0};
  std::array<std::uint8_t, kMoveRequestBytes> move_bytes{};
  putMoveRequest(move_bytes, move);
  EXPECT_EQ(move_bytes[0], 2);
  EXPECT_EQ(move_bytes[4], 1);
  EXPECT_EQ(doubleAt(move_bytes, 8), 10.0);
  EXPECT_EQ(doubleAt(move_bytes, 8 + 5 * 8), 3.0);
  const MoveRequest move_back = getMoveRequest(move_bytes);
  EXPECT_EQ(move_back.generator, MoveGenerator::kJointVelocity);
  EXPECT_EQ(move_back.goal_deviation, move.goal_deviation);

  CollisionThresholds thresholds;
  thresholds.torque_collision_nominal[6] = 42.0;
  thresholds.force_collision_nominal[2] = 33.0;
  std::array<std::uint8_t, kCollisionRequestBytes> collision{};
  putCollisionThresholds(collision, thresholds);
  EXPECT_EQ(doubleAt(collision, 8 * (3 * 7 + 6)), 42.0);
  EXPECT_EQ(doubleAt(collision, 8 * (4 * 7 + 3 * 6 + 2)), 33.0);
  const CollisionThresholds collision_back = getCollisionThresholds(collision);
  EXPECT_EQ(collision_back.torque_collision_nominal, thresholds.torque_collision_nominal);
  EXPECT_EQ(collision_back.force_collision_nominal, thresholds.force_collision_nominal);
}

TEST(FciProtocol, AnyNonZeroFlagByteReadsTrue) {
  std::array<std::uint8_t, kCommandBytes> bytes{};
  bytes[8 + 38 * 8 + 1] = 0x7f;
  EXPECT_TRUE(getRobotCommand(bytes).motion_finished);
}

}  // namespace
}  // namespace comply::franka::fci
