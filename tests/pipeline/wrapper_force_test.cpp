// Force axes through the wrapper on the FR3: a command selecting them reaches the law as a force
// source (no spring along them, the push in the feedforward, no force axes left for the law);
// a selection other than 0/1 is refused with its reason and leaves the command in force; a chunk
// cannot carry them; the watchdog's hold releases them; a source that cannot exist is refused
// when the controller is resolved.

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

const comply_cartesian_command& lawCommand(const CartesianWrapper& wrapper) {
  return std::get<comply_cartesian_command>(wrapper.controller().lawBus());
}

/// Force along base z (task frame = base), 12 N exerted downwards, the reference 3 cm below.
CartesianCommand pressDown(const MeasuredPose& measured, double stamp_s) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition | CommandField::kForce;
  command.position = measured.tcp_position + Eigen::Vector3d(0.0, 0.0, -0.03);
  command.orientation = measured.tcp_orientation;
  command.force_axes[2] = 1.0;
  command.wrench_target[2] = -12.0;
  return command;
}

class WrapperForce : public ::testing::Test {
 protected:
  void start(const std::string& lines) {
    wrapper_ = std::make_unique<CartesianWrapper>(
        // The state repeats bit for bit here, which is no stale stream.
        fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0.0\n" + lines));
    state_ = restingAt(wrapper_->controller(), fr3Home());
    wrapper_->activate(state_);
    cycle();
  }
  void cycle() { ASSERT_EQ(wrapper_->update(state_, kPeriod, torque_.span()), CycleStatus::kOk); }

  std::unique_ptr<CartesianWrapper> wrapper_;
  JointState state_;
  TorqueBuffer torque_;
};

TEST_F(WrapperForce, TheLawReadsAForceSourceAlongTheSelectedAxis) {
  start("");
  const MeasuredPose home = wrapper_->measuredPose();
  ASSERT_TRUE(wrapper_->submit(pressDown(home, 1.0)).accepted);
  cycle();
  const comply_cartesian_command& law = lawCommand(*wrapper_);
  // No wrench estimate (no observer, no sensor): the push is the target alone.
  EXPECT_DOUBLE_EQ(law.wrench_feedforward[2], -12.0);
  EXPECT_NEAR(law.position[2], home.tcp_position.z(), 1e-12) << "no spring along z";
  for (const double axis : law.force_axes) {
    EXPECT_EQ(axis, 0.0);
  }
  // The command in force keeps what was sent.
  const auto& in_force = std::get<comply_cartesian_command>(wrapper_->controller().activeCommand());
  EXPECT_EQ(in_force.force_axes[2], 1.0);
  EXPECT_NEAR(in_force.position[2], home.tcp_position.z() - 0.03, 1e-12);
  // At rest with no pose error, what the cycle adds to gravity is J^T of the push (the nullspace
  // at its target and at rest: nothing) - a force source. Cycles at the same state let the
  // torque-rate limit catch up.
  for (int i = 0; i < 100; ++i) {
    cycle();
  }
  const model::Data& data = wrapper_->controller().modelData();
  Vector6d push = Vector6d::Zero();
  push[2] = -12.0;
  const JointVector expected = data.jacobian.leftCols(kFr3Dof).transpose() * push;
  COMPLY_EXPECT_JOINTS_NEAR(
      JointVector(torque_.values - gravityAt(wrapper_->controller(), fr3Home())), expected, 1e-6);
}

TEST_F(WrapperForce, ASelectionOtherThanZeroOrOneIsRefused) {
  start("");
  const MeasuredPose home = wrapper_->measuredPose();
  ASSERT_TRUE(wrapper_->submit(pressDown(home, 1.0)).accepted);
  CartesianCommand half = pressDown(home, 2.0);
  half.force_axes[4] = 0.5;
  const Verdict verdict = wrapper_->submit(half);
  EXPECT_FALSE(verdict.accepted);
  EXPECT_EQ(verdict.reason, RejectionReason::kOutOfRange);
  EXPECT_NE(verdict.message.find("force_axes entries must be 0 or 1"), std::string::npos)
      << verdict.message;
  EXPECT_NE(verdict.message.find("entry 4 is 0.5"), std::string::npos) << verdict.message;
  cycle();
  const auto& in_force = std::get<comply_cartesian_command>(wrapper_->controller().activeCommand());
  EXPECT_EQ(in_force.force_axes[4], 0.0) << "the last valid command stays in force";
  EXPECT_EQ(in_force.force_axes[2], 1.0);
}

TEST_F(WrapperForce, TheWatchdogsHoldReleasesTheForceAxes) {
  start("command_timeout_s: 0.05\ntimeout_behavior: hold\n");
  ASSERT_TRUE(wrapper_->submit(pressDown(wrapper_->measuredPose(), 1.0)).accepted);
  cycle();
  EXPECT_DOUBLE_EQ(lawCommand(*wrapper_).wrench_feedforward[2], -12.0);
  for (int i = 0; i < 60; ++i) {  // past command_timeout_s
    cycle();
  }
  ASSERT_GE(wrapper_->diagnostics().watchdog_timeouts, 1U);
  EXPECT_EQ(lawCommand(*wrapper_).wrench_feedforward[2], 0.0)
      << "an arm whose sender went quiet stops pressing";
}

// In FAULT no law runs: what the law would read is the command in force again, not the force
// stage's last cycle (state samples and recordings read it).
TEST_F(WrapperForce, InFaultTheLawsCommandIsTheCommandInForce) {
  start("");
  ASSERT_TRUE(wrapper_->submit(pressDown(wrapper_->measuredPose(), 1.0)).accepted);
  cycle();
  EXPECT_EQ(lawCommand(*wrapper_).force_axes[2], 0.0) << "the stage acted";
  JointState broken = state_;
  broken.position[3] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_EQ(wrapper_->update(broken, kPeriod, torque_.span()), CycleStatus::kFault);
  EXPECT_EQ(lawCommand(*wrapper_).force_axes[2], 1.0);
}

TEST_F(WrapperForce, AChunkCannotCarryForceAxes) {
  start("");
  CartesianChunk chunk;
  chunk.stamp_s = 1.0;
  chunk.fields = CommandField::kPosition | CommandField::kForce;
  chunk.waypoints.push_back({0.1, pressDown(wrapper_->measuredPose(), 0.0)});
  const Verdict verdict = wrapper_->submitChunk(chunk, 0.0);
  EXPECT_FALSE(verdict.accepted);
  EXPECT_EQ(verdict.reason, RejectionReason::kInvalidChunk);
  EXPECT_NE(verdict.message.find("force"), std::string::npos) << verdict.message;
}

TEST(WrapperForceConfig, AnObserverSourceWithoutTheObserverIsRefused) {
  try {
    (void)resolveController(
        fr3Config(kCartesianImpedancePlugin, "force_control:\n  source: observer\n"));
    FAIL() << "resolved";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("force_control.source"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("observer.enabled is false"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace comply::pipeline::test
