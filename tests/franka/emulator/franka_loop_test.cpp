// comply's Cartesian impedance on the emulated FR3 through `--hardware franka` (franka_rig.hpp):
// a Cartesian target reached on the robot's torque control; the robot's reflexes and a lost
// link of commands as FAULTs naming them, a reset that runs the robot's recovery and re-arms; the
// collision thresholds raised for a push the robot's default would have stopped.

#include <gtest/gtest.h>

#include <cstdio>

#include "comply/hardware/loop_clock.hpp"
#include "franka_rig.hpp"

namespace comply::franka::test {
namespace {

CartesianCommand poseCommand(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                             double stamp_s) {
  CartesianCommand command = CartesianCommand::zero(7);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition;
  command.position = position;
  command.orientation = orientation;
  return command;
}

TEST(FrankaLoop, ACartesianTargetOnTheRobotsTorqueControl) {
  FrankaEmulator emulator(waitingEmulator());
  FrankaRig rig(emulator);
  const MeasuredPose home = rig.wrapper.measuredPose();
  const Eigen::Vector3d target = home.tcp_position + Eigen::Vector3d(0.03, -0.02, 0.02);
  ASSERT_TRUE(
      rig.wrapper
          .submit(poseCommand(target, home.tcp_orientation, hardware::monotonicSeconds() + 10.0))
          .accepted);
  std::this_thread::sleep_for(std::chrono::seconds(3));
  const double error_m = (emulator.state().tcp.translation() - target).norm();
  EXPECT_EQ(rig.state(), pipeline::WrapperState::kActive);
  rig.loop.stop();
  rig.thread = {};  // the loop's statistics are its thread's until it ends
  const hardware::LoopStats loop = rig.loop.stats();
  const FrankaArmStats link = rig.arm().stats();
  std::printf(
      "target 4.1 cm away: TCP error %.2f mm after 3 s; %lu cycles, %lu skipped states, "
      "%lu lost commands\n",
      error_m * 1e3, static_cast<unsigned long>(loop.cycles),
      static_cast<unsigned long>(link.skipped), static_cast<unsigned long>(emulator.stats().lost));
  EXPECT_LT(error_m, 3e-3);
  EXPECT_EQ(link.controls, 1U);
  EXPECT_EQ(emulator.stats().lost, 0U);
  EXPECT_EQ(link.skipped, 0U);
}

TEST(FrankaLoop, AReflexIsAFaultThatNamesItAndAResetRecoversTheRobot) {
  FrankaEmulator emulator(waitingEmulator());
  FrankaRig rig(emulator);
  ASSERT_TRUE(eventually([&] { return emulator.state().torque_control; }, 2.0));
  emulator.reflex(6);  // joint_reflex
  ASSERT_TRUE(rig.faultsWith("robot: reflex joint_reflex")) << rig.wrapper.diagnostics().last_fault;
  rig.wrapper.reset();  // refused: the robot is in Reflex
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(rig.state(), pipeline::WrapperState::kFault);
  // A reset request runs the robot's recovery first (the live host does), then the reset.
  EXPECT_EQ(rig.arm().recover(), "");
  EXPECT_EQ(emulator.stats().recoveries, 1U);
  EXPECT_EQ(rig.state(), pipeline::WrapperState::kFault) << "re-armed without a reset";
  rig.wrapper.reset();
  ASSERT_TRUE(eventually([&] { return rig.state() == pipeline::WrapperState::kActive; }, 2.0));
  ASSERT_TRUE(eventually([&] { return emulator.state().torque_control; }, 2.0));
  EXPECT_EQ(rig.arm().stats().controls, 2U);
}

TEST(FrankaLoop, LostCommandsAreACommunicationFault) {
  FrankaEmulator emulator(waitingEmulator());
  FrankaRig rig(emulator);
  ASSERT_TRUE(eventually([&] { return emulator.state().torque_control; }, 2.0));
  emulator.loseCommands(25);  // lost on the way: 20 in a row end the motion
  ASSERT_TRUE(rig.faultsWith("robot: communication_constraints_violation"))
      << rig.wrapper.diagnostics().last_fault;
  EXPECT_EQ(emulator.stats().last_reflex, "communication_constraints_violation");
  EXPECT_EQ(rig.arm().recover(), "");
  rig.wrapper.reset();
  ASSERT_TRUE(eventually([&] { return rig.state() == pipeline::WrapperState::kActive; }, 2.0));
}

TEST(FrankaLoop, RaisedCollisionThresholdsLetAnIntendedPushThrough) {
  FrankaEmulator emulator(waitingEmulator());
  FrankaRig rig(emulator, {"collision_force_n=20"});
  ASSERT_TRUE(eventually([&] { return emulator.state().torque_control; }, 2.0));
  // Raised for the pressing phase, at run time: the torque control ends for the change and
  // starts again.
  ASSERT_TRUE(rig.arm().requestCollisionThresholds(frankaCollisionThresholds(80.0, 60.0)));
  ASSERT_TRUE(eventually([&] { return rig.arm().stats().threshold_changes == 1; }, 2.0));
  EXPECT_DOUBLE_EQ(emulator.stats().collision.force_collision_nominal[2], 60.0);
  Vector6d push = Vector6d::Zero();
  push[2] = -35.0;  // N: above the 20 N the run started with
  emulator.push(push);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(emulator.stats().reflexes, 0U);
  EXPECT_EQ(rig.state(), pipeline::WrapperState::kActive) << rig.wrapper.diagnostics().last_fault;
  // Back to 20 N for the next phase: the same push is a reflex now.
  emulator.push(Vector6d::Zero());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_TRUE(rig.arm().requestCollisionThresholds(frankaCollisionThresholds(80.0, 20.0)));
  ASSERT_TRUE(eventually([&] { return rig.arm().stats().threshold_changes == 2; }, 2.0));
  emulator.push(push);
  ASSERT_TRUE(rig.faultsWith("robot: reflex cartesian_reflex"))
      << rig.wrapper.diagnostics().last_fault;
  emulator.push(Vector6d::Zero());
}

TEST(FrankaLoop, TheRobotsThresholdsFollowTheContactACommandLetsThrough) {
  FrankaEmulator emulator(waitingEmulator());
  pipeline::WrapperConfig config = frankaConfig();
  config.reflex.enabled = true;  // comply's own contact reflex: the file's 20 N, at most 60 N
  FrankaRig rig(emulator, {}, config);
  const auto robotsForceThreshold = [&] {
    return emulator.stats().collision.force_collision_nominal[2];
  };
  // The robot's thresholds sit 1.5 x above comply's reflex: comply's hold acts first.
  ASSERT_TRUE(eventually([&] { return robotsForceThreshold() == 30.0; }, 2.0))
      << robotsForceThreshold();
  const MeasuredPose home = rig.wrapper.measuredPose();
  const double start_s = hardware::monotonicSeconds();
  CartesianCommand press = poseCommand(home.tcp_position, home.tcp_orientation, start_s + 10.0);
  press.fields = press.fields | CommandField::kReflex;
  std::fill(std::begin(press.reflex_force), std::end(press.reflex_force), 50.0);
  ASSERT_TRUE(rig.wrapper.submit(press).accepted);
  ASSERT_TRUE(eventually([&] { return robotsForceThreshold() == 75.0; }, 2.0))
      << robotsForceThreshold();
  Vector6d push = Vector6d::Zero();
  push[2] = -35.0;  // N: above the robot's default 20 N, within the phase's 50 N
  emulator.push(push);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(emulator.stats().reflexes, 0U);
  EXPECT_EQ(rig.wrapper.diagnostics().reflex_trips, 0U);
  EXPECT_EQ(rig.state(), pipeline::WrapperState::kActive) << rig.wrapper.diagnostics().last_fault;
  emulator.push(Vector6d::Zero());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // The phase ends: the file's 20 N again, the robot's 30 N. A 25 N push is comply's reflex's.
  CartesianCommand after = poseCommand(home.tcp_position, home.tcp_orientation, start_s + 11.0);
  after.fields = after.fields | CommandField::kReflex;  // 0: the file's thresholds
  ASSERT_TRUE(rig.wrapper.submit(after).accepted);
  ASSERT_TRUE(eventually([&] { return robotsForceThreshold() == 30.0; }, 2.0))
      << robotsForceThreshold();
  push[2] = -25.0;
  emulator.push(push);
  ASSERT_TRUE(eventually([&] { return rig.wrapper.diagnostics().reflex_trips >= 1; }, 2.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(emulator.stats().reflexes, 0U) << emulator.stats().last_reflex;
  EXPECT_GE(rig.arm().stats().threshold_changes, 3U);
  emulator.push(Vector6d::Zero());
}

}  // namespace
}  // namespace comply::franka::test
