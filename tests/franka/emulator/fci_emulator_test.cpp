// comply's FCI client against the emulated robot (franka_emulator.hpp): the handshake, states,
// the torque control, and the robot's rules (a late or lost command, reflexes, setters only
// between motions).

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "comply/franka/franka_arm.hpp"
#include "comply/hardware/backend.hpp"
#include "fci_rig.hpp"

namespace comply::franka {
namespace {

using testing::connect;
using testing::emulatorOptions;
using testing::start;

/// Answers the state read last and `count` more with `torque`, as a control loop does.
void answer(FrankaSession& session, int count, const std::array<double, 7>& torque = {}) {
  FrankaSample sample;
  for (int state = 0; state < count; ++state) {
    ASSERT_TRUE(session.writeTorque(torque));
    ASSERT_TRUE(session.read(sample, 1.0)) << session.failure();
  }
}

/// Reads states until `done` says so (at most `limit_s`); the last one.
template <typename Done>
FrankaSample readUntil(FrankaSession& session, Done done, double limit_s = 3.0) {
  FrankaSample sample;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  while (std::chrono::steady_clock::now() < until) {
    if (session.read(sample, 0.5) && done(sample)) {
      return sample;
    }
  }
  ADD_FAILURE() << "not within " << limit_s << " s";
  return sample;
}

TEST(FciEmulator, AnotherProtocolVersionIsRefusedWithTheRobots) {
  FrankaEmulator robot(emulatorOptions(0.0));
  const int client = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in where{};
  where.sin_family = AF_INET;
  where.sin_port = htons(robot.commandPort());
  where.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(client, reinterpret_cast<sockaddr*>(&where), sizeof where), 0);
  std::array<std::uint8_t, fci::kHeaderBytes + 4> request{};
  fci::putHeader(std::span<std::uint8_t, fci::kHeaderBytes>(request.data(), fci::kHeaderBytes),
                 {fci::Command::kConnect, 0, static_cast<std::uint32_t>(request.size())});
  const std::uint16_t old_version = 5;
  const std::uint16_t udp_port = 40000;
  std::memcpy(request.data() + 12, &old_version, 2);
  std::memcpy(request.data() + 14, &udp_port, 2);
  ASSERT_EQ(::send(client, request.data(), request.size(), 0), 16);
  std::array<std::uint8_t, 15> response{};
  ASSERT_EQ(::recv(client, response.data(), response.size(), MSG_WAITALL), 15);
  const fci::Header header =
      fci::getHeader(std::span<const std::uint8_t, fci::kHeaderBytes>(response.data(), 12));
  EXPECT_EQ(header.command, fci::Command::kConnect);
  EXPECT_EQ(header.size, 15U);
  EXPECT_EQ(response[12], 1);  // incompatible library version
  std::uint16_t version = 0;
  std::memcpy(&version, response.data() + 13, 2);
  EXPECT_EQ(version, fci::kProtocolVersion);
  ::close(client);
  EXPECT_EQ(robot.stats().connections, 0U);
}

TEST(FciEmulator, ConnectedClientGetsTheStateEveryMillisecond) {
  FrankaEmulator robot(emulatorOptions(0.0));
  auto session = connect(robot);
  EXPECT_NE(session->description().find("protocol version 7"), std::string::npos);
  FrankaSample first;
  ASSERT_TRUE(session->read(first, 1.0));
  FrankaSample sample;
  for (int state = 0; state < 50; ++state) {
    ASSERT_TRUE(session->read(sample, 1.0));
  }
  EXPECT_GE(sample.time_ms, first.time_ms + 50);  // one per ms, the newest each time
  EXPECT_EQ(sample.robot_mode, fci::RobotMode::kIdle);
  EXPECT_FALSE(sample.torque_control);
  const FrankaEmulatorState state = robot.state();
  for (int joint = 0; joint < 7; ++joint) {
    EXPECT_NEAR(sample.q[static_cast<std::size_t>(joint)], state.position[joint], 1e-3);
  }
  // The joints' torque sensors carry the arm's weight while the robot holds it.
  EXPECT_GT(std::abs(sample.tau_J[1]), 1.0);
  EXPECT_EQ(robot.stats().connections, 1U);
}

TEST(FciEmulator, TorqueControlStartsRunsAndFinishes) {
  FrankaEmulator robot(emulatorOptions(0.5));
  auto session = connect(robot);
  ASSERT_EQ(start(*session), "");
  EXPECT_TRUE(robot.state().torque_control);
  const JointVector start = robot.state().position;
  answer(*session, 300);  // zero torque: the robot's gravity compensation carries the arm
  const FrankaEmulatorState state = robot.state();
  EXPECT_EQ(state.mode, fci::RobotMode::kMove);
  EXPECT_LT((state.position - start).norm(), 0.02);
  // A torque moves the joint it is sent to.
  std::array<double, 7> twist{};
  twist[6] = 0.5;
  answer(*session, 200, twist);
  EXPECT_GT(robot.state().position[6] - start[6], 0.05);
  // Setters wait for the end of a motion, as the robot's do.
  EXPECT_NE(session->setCollisionThresholds(frankaCollisionThresholds(40.0, 40.0)), "");
  ASSERT_EQ(session->stopTorqueControl(), "");
  EXPECT_FALSE(robot.state().torque_control);
  EXPECT_EQ(robot.state().mode, fci::RobotMode::kIdle);
  EXPECT_EQ(session->setCollisionThresholds(frankaCollisionThresholds(40.0, 40.0)), "");
  EXPECT_DOUBLE_EQ(robot.stats().collision.torque_collision_nominal[0], 40.0);
  const FrankaEmulatorStats stats = robot.stats();
  EXPECT_EQ(stats.motions, 1U);
  EXPECT_EQ(stats.lost, 0U);
  EXPECT_GE(stats.answered, 500U);
}

TEST(FciEmulator, StatesWithoutACommandEndTheMotionWithACommunicationError) {
  FrankaEmulator robot(emulatorOptions(0.0));  // the robot's own rule: no waiting
  auto session = connect(robot);
  ASSERT_EQ(start(*session), "");
  answer(*session, 50);
  // The client stops answering (a stalled loop): after 20 states in a row, a reflex.
  const FrankaSample stopped = readUntil(
      *session, [](const FrankaSample& s) { return s.robot_mode == fci::RobotMode::kReflex; });
  EXPECT_FALSE(stopped.torque_control);
  EXPECT_TRUE(stopped.errors[25]);
  EXPECT_TRUE(stopped.last_motion_errors[25]);
  EXPECT_LT(stopped.command_success_rate, 0.85);
  const FrankaEmulatorStats stats = robot.stats();
  EXPECT_EQ(stats.last_reflex, "communication_constraints_violation");
  EXPECT_GE(stats.longest_lost_run, 20U);
  EXPECT_EQ(stats.reflexes, 1U);
  // No motion starts until the error is recovered.
  EXPECT_NE(start(*session), "");
  ASSERT_EQ(session->recover(), "");
  const FrankaSample idle = readUntil(
      *session, [](const FrankaSample& s) { return s.robot_mode == fci::RobotMode::kIdle; });
  EXPECT_FALSE(idle.errors[25]);
  ASSERT_EQ(start(*session), "");
  answer(*session, 20);
  EXPECT_EQ(robot.stats().recoveries, 1U);
}

TEST(FciEmulator, FewLostCommandsAreRiddenThroughAndCounted) {
  FrankaEmulator robot(emulatorOptions(0.5));
  auto session = connect(robot);
  ASSERT_EQ(start(*session), "");
  answer(*session, 20);
  robot.loseCommands(5);
  answer(*session, 30);
  FrankaSample sample;
  ASSERT_TRUE(session->writeTorque(std::array<double, 7>{}));
  ASSERT_TRUE(session->read(sample, 1.0));
  EXPECT_EQ(sample.robot_mode, fci::RobotMode::kMove);
  EXPECT_LE(sample.command_success_rate, 0.96);
  EXPECT_EQ(robot.stats().lost, 5U);
  EXPECT_EQ(robot.stats().reflexes, 0U);
  // States lost on the way: the client sees the gap in the robot's clock.
  robot.dropStates(3);
  ASSERT_TRUE(session->writeTorque(std::array<double, 7>{}));
  FrankaSample after;
  ASSERT_TRUE(session->read(after, 1.0));
  EXPECT_EQ(after.time_ms, sample.time_ms + 4);
  EXPECT_EQ(robot.stats().dropped, 3U);
}

TEST(FciEmulator, AnInjectedReflexEndsTheMotionNamingIt) {
  FrankaEmulator robot(emulatorOptions(0.5));
  auto session = connect(robot);
  ASSERT_EQ(start(*session), "");
  answer(*session, 20);
  robot.reflex(6);  // joint_reflex
  const FrankaSample stopped = readUntil(
      *session, [](const FrankaSample& s) { return s.robot_mode == fci::RobotMode::kReflex; });
  EXPECT_TRUE(stopped.errors[6]);
  EXPECT_FALSE(stopped.torque_control);
  EXPECT_FALSE(session->writeTorque(std::array<double, 7>{}));  // no motion to answer
  EXPECT_EQ(session->stopTorqueControl(), "");
  ASSERT_EQ(session->recover(), "");
}

TEST(FciEmulator, APushAboveTheCollisionThresholdIsAReflexAndRaisedThresholdsLetItPass) {
  FrankaEmulator robot(emulatorOptions(0.5));
  auto session = connect(robot);
  ASSERT_EQ(session->setCollisionThresholds(frankaCollisionThresholds(100.0, 20.0)), "");
  ASSERT_EQ(start(*session), "");
  answer(*session, 20);
  Vector6d push = Vector6d::Zero();
  push[2] = -35.0;  // N, down on the tool
  robot.push(push);
  const FrankaSample stopped = readUntil(
      *session, [](const FrankaSample& s) { return s.robot_mode == fci::RobotMode::kReflex; });
  EXPECT_TRUE(stopped.errors[7]);  // cartesian_reflex
  EXPECT_EQ(robot.stats().last_reflex, "cartesian_reflex");
  robot.push(Vector6d::Zero());
  ASSERT_EQ(session->recover(), "");
  (void)readUntil(*session,
                  [](const FrankaSample& s) { return s.robot_mode == fci::RobotMode::kIdle; });
  ASSERT_EQ(session->setCollisionThresholds(frankaCollisionThresholds(100.0, 60.0)), "");
  ASSERT_EQ(start(*session), "");
  robot.push(push);
  FrankaSample sample;
  for (int state = 0; state < 300; ++state) {
    ASSERT_TRUE(session->writeTorque(std::array<double, 7>{}));
    ASSERT_TRUE(session->read(sample, 1.0));
  }
  EXPECT_EQ(sample.robot_mode, fci::RobotMode::kMove);
  // The robot's sign: what the arm exerts, against the push.
  EXPECT_NEAR(sample.O_F_ext_hat_K[2], 35.0, 1.0);
  EXPECT_EQ(robot.stats().reflexes, 1U);
  robot.push(Vector6d::Zero());
}

TEST(FciEmulator, AClosedConnectionEndsTheClientsLink) {
  FrankaEmulator robot(emulatorOptions(0.0));
  auto session = connect(robot);
  FrankaSample sample;
  ASSERT_TRUE(session->read(sample, 1.0));
  robot.closeConnection();
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  bool failed = false;
  while (!failed && std::chrono::steady_clock::now() < until) {
    failed = !session->read(sample, 0.05);
  }
  ASSERT_TRUE(failed);
  ASSERT_NE(session->failure(), nullptr);
  // And the robot takes a new client.
  auto again = connect(robot);
  ASSERT_TRUE(again->read(sample, 1.0));
  EXPECT_EQ(robot.stats().connections, 2U);
}

}  // namespace
}  // namespace comply::franka
