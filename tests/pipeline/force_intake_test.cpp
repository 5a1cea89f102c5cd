// Force axes at the intake and where they end, on the FR3: the jump check leaves out the reference
// along the axes that stay force axes (in their task frame; the cycle's and the intake's
// selection both), and checks in full an axis a command turns off; wherever a force axis ends (the
// watchdog's hold, a command clearing it) the reference along it is the measured pose; a force
// target or feedforward above what the arm exerts at the measured pose is refused, and the force
// stage never commands more.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "comply/pipeline/wrench_bound.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

/// Force along task z, 10 N upwards, the target `offset` from the measured pose.
CartesianCommand pushUp(const MeasuredPose& measured, double stamp_s,
                        const Eigen::Vector3d& offset) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition | CommandField::kForce;
  command.position = measured.tcp_position + offset;
  command.orientation = measured.tcp_orientation;
  command.force_axes[2] = 1.0;
  command.wrench_target[2] = 10.0;
  return command;
}

/// A position-only command `offset` from the measured pose.
CartesianCommand moveTo(const MeasuredPose& measured, double stamp_s,
                        const Eigen::Vector3d& offset) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition;
  command.position = measured.tcp_position + offset;
  command.orientation = measured.tcp_orientation;
  return command;
}

const comply_cartesian_command& inForce(const CartesianWrapper& wrapper) {
  return std::get<comply_cartesian_command>(wrapper.controller().activeCommand());
}

class ForceIntake : public ::testing::Test {
 protected:
  void start(const std::string& lines = {}) {
    wrapper_ = std::make_unique<CartesianWrapper>(
        fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0.0\n" + lines));
    state_ = restingAt(wrapper_->controller(), fr3Home());
    wrapper_->activate(state_);
    cycle();
    home_ = wrapper_->measuredPose();
  }
  void cycle() { ASSERT_EQ(wrapper_->update(state_, kPeriod, torque_.span()), CycleStatus::kOk); }

  std::unique_ptr<CartesianWrapper> wrapper_;
  JointState state_;
  TorqueBuffer torque_;
  MeasuredPose home_;
};

TEST_F(ForceIntake, AlongAForceAxisTheTargetIsNotCheckedAgainstTheMeasuredPose) {
  start();
  // 30 cm along the force axis (limit 10 cm): accepted; 30 cm along x with it: refused.
  EXPECT_TRUE(wrapper_->submit(pushUp(home_, 1.0, {0.0, 0.0, 0.3})).accepted);
  const Verdict sideways = wrapper_->submit(pushUp(home_, 2.0, {0.3, 0.0, 0.3}));
  EXPECT_FALSE(sideways.accepted);
  EXPECT_EQ(sideways.reason, RejectionReason::kPoseJump);
  EXPECT_NE(sideways.message.find("0.3 m"), std::string::npos) << sideways.message;
  cycle();
  // With z in force, a position-only command far along z is accepted, along x still not.
  EXPECT_TRUE(wrapper_->submit(moveTo(home_, 3.0, {0.0, 0.0, 0.4})).accepted);
  EXPECT_EQ(wrapper_->submit(moveTo(home_, 4.0, {0.2, 0.0, 0.0})).reason,
            RejectionReason::kPoseJump);
  // A command turning the axis off is checked in full.
  CartesianCommand off = moveTo(home_, 5.0, {0.0, 0.0, 0.3});
  off.fields = off.fields | CommandField::kForce;
  EXPECT_EQ(wrapper_->submit(off).reason, RejectionReason::kPoseJump);
}

TEST_F(ForceIntake, TheForceAxesAreTheTaskFramesAndRotationalToo) {
  start();
  // Task frame: base turned 90 degrees about x, so task z is base -y. Force along task z and
  // about task z: 30 cm along base y and 1 rad about base -y are the force axes' (limits 0.1 m,
  // 0.6 rad); 30 cm along base z is not.
  CartesianCommand command = pushUp(home_, 1.0, {0.0, 0.3, 0.0});
  command.fields = command.fields | CommandField::kTaskFrame;
  command.task_frame = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  command.force_axes[5] = 1.0;
  command.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(1.0, -Eigen::Vector3d::UnitY())) * home_.tcp_orientation;
  EXPECT_TRUE(wrapper_->submit(command).accepted);
  CartesianCommand up = command;
  up.stamp_s = 2.0;
  up.position = home_.tcp_position + Eigen::Vector3d(0.0, 0.0, 0.3);
  EXPECT_EQ(wrapper_->submit(up).reason, RejectionReason::kPoseJump);
  CartesianCommand tilted = command;
  tilted.stamp_s = 3.0;
  tilted.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX())) * home_.tcp_orientation;
  EXPECT_EQ(wrapper_->submit(tilted).reason, RejectionReason::kPoseJump);
}

TEST_F(ForceIntake, AnAxisTheIntakeHasTurnedOffIsCheckedBeforeTheCycleTakesIt) {
  start();
  ASSERT_TRUE(wrapper_->submit(pushUp(home_, 1.0, Eigen::Vector3d::Zero())).accepted);
  cycle();
  CartesianCommand off = moveTo(home_, 2.0, Eigen::Vector3d::Zero());
  off.fields = off.fields | CommandField::kForce;
  const Verdict turned_off = wrapper_->submit(off);
  ASSERT_TRUE(turned_off.accepted) << turned_off.message;
  // Not yet taken: the cycle still holds z under force, the intake does not.
  EXPECT_EQ(wrapper_->submit(moveTo(home_, 3.0, {0.0, 0.0, 0.3})).reason,
            RejectionReason::kPoseJump);
}

TEST_F(ForceIntake, TheWatchdogEndsAForceAxisHoldingTheMeasuredPose) {
  start("command_timeout_s: 0.05\ntimeout_behavior: hold\n");
  // The reference 15 cm above: the arm is where the force took it, the sender's position stale.
  ASSERT_TRUE(wrapper_->submit(pushUp(home_, 1.0, {0.01, 0.0, -0.15})).accepted);
  cycle();
  EXPECT_NEAR(inForce(*wrapper_).position[2], home_.tcp_position.z() - 0.15, 1e-12);
  for (int i = 0; i < 60; ++i) {  // past command_timeout_s
    cycle();
  }
  ASSERT_GE(wrapper_->diagnostics().watchdog_timeouts, 1U);
  const comply_cartesian_command& held = inForce(*wrapper_);
  EXPECT_EQ(held.force_axes[2], 0.0) << "the force axis ended";
  EXPECT_NEAR(held.position[2], home_.tcp_position.z(), 1e-12) << "held where the arm is";
  EXPECT_NEAR(held.position[0], home_.tcp_position.x() + 0.01, 1e-12) << "x is impedance";
  EXPECT_NEAR(held.position[1], home_.tcp_position.y(), 1e-12);
  const auto& law = std::get<comply_cartesian_command>(wrapper_->controller().lawBus());
  EXPECT_NEAR(law.position[2], home_.tcp_position.z(), 1e-12);
}

TEST_F(ForceIntake, ACommandClearingAForceAxisHoldsTheMeasuredPoseAlongIt) {
  start();
  ASSERT_TRUE(wrapper_->submit(pushUp(home_, 1.0, {0.0, 0.0, 0.25})).accepted);
  cycle();
  CartesianCommand off = CartesianCommand::zero(kFr3Dof);
  off.stamp_s = 2.0;
  off.fields = CommandField::kForce;
  ASSERT_TRUE(wrapper_->submit(off).accepted);
  cycle();
  EXPECT_EQ(inForce(*wrapper_).force_axes[2], 0.0);
  EXPECT_NEAR(inForce(*wrapper_).position[2], home_.tcp_position.z(), 1e-12);
}

TEST_F(ForceIntake, AWrenchAboveWhatTheArmExertsIsRefused) {
  start();
  CartesianCommand target = pushUp(home_, 1.0, Eigen::Vector3d::Zero());
  target.wrench_target[2] = 1e4;
  const Verdict refused = wrapper_->submit(target);
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.reason, RejectionReason::kOutOfRange);
  EXPECT_NE(refused.message.find("wrench_target of 10000 N"), std::string::npos) << refused.message;
  EXPECT_NE(refused.message.find("fr3"), std::string::npos) << refused.message;
  CartesianCommand feedforward = CartesianCommand::zero(kFr3Dof);
  feedforward.stamp_s = 2.0;
  feedforward.fields = CommandField::kWrenchFeedforward;
  feedforward.wrench_feedforward[2] = -1e4;
  const Verdict pushed = wrapper_->submit(feedforward);
  EXPECT_EQ(pushed.reason, RejectionReason::kOutOfRange);
  EXPECT_NE(pushed.message.find("wrench_feedforward of 10000 N"), std::string::npos)
      << pushed.message;
  EXPECT_EQ(wrapper_->diagnostics().commands_accepted, 0U);
  // At the bound along z exactly: accepted; a little above: refused.
  const model::Data& data = wrapper_->controller().modelData();
  Vector6d up = Vector6d::Zero();
  up[2] = 1.0;
  const double bound =
      1.0 / effortRatio(data.jacobian, up, wrapper_->controller().effortLimit(), kFr3Dof).ratio;
  EXPECT_GT(bound, 10.0);
  EXPECT_LT(bound, 1e4);
  target.stamp_s = 3.0;
  target.wrench_target[2] = 0.999 * bound;
  EXPECT_TRUE(wrapper_->submit(target).accepted);
  target.stamp_s = 4.0;
  target.wrench_target[2] = 1.001 * bound;
  EXPECT_EQ(wrapper_->submit(target).reason, RejectionReason::kOutOfRange);
  // Their sum counts: a feedforward that is within the bound alone, but not with the target.
  feedforward.stamp_s = 5.0;
  feedforward.wrench_feedforward[2] = 0.5 * bound;
  EXPECT_EQ(wrapper_->submit(feedforward).reason, RejectionReason::kOutOfRange);
}

TEST_F(ForceIntake, TheForceStageNeverCommandsMoreThanTheArmExertsWhereItIs) {
  start();
  // A target just within the bound at home; then the arm is elsewhere, where it is not.
  const Controller& controller = wrapper_->controller();
  Vector6d up = Vector6d::Zero();
  up[2] = 1.0;
  const double bound =
      1.0 /
      effortRatio(controller.modelData().jacobian, up, controller.effortLimit(), kFr3Dof).ratio;
  CartesianCommand target = pushUp(home_, 1.0, Eigen::Vector3d::Zero());
  target.wrench_target[2] = 0.99 * bound;
  ASSERT_TRUE(wrapper_->submit(target).accepted);
  state_ = restingAt(controller, offset(fr3Home(), 5, 0.8));
  cycle();
  const model::Data& data = controller.modelData();
  ASSERT_GT(effortRatio(data.jacobian, 0.99 * bound * up, controller.effortLimit(), kFr3Dof).ratio,
            1.0)
      << "the pose must carry less along z";
  const auto& law = std::get<comply_cartesian_command>(controller.lawBus());
  const Vector6d pushed = Eigen::Map<const Vector6d>(law.wrench_feedforward);
  EXPECT_NEAR(effortRatio(data.jacobian, pushed, controller.effortLimit(), kFr3Dof).ratio, 1.0,
              1e-9);
  EXPECT_GT(pushed[2], 0.0) << "scaled along its direction";
}

TEST(WrenchBound, AWrenchAboveTheEffortLimitsIsScaledOntoThem) {
  Jacobian jacobian = Jacobian::Zero(6, 2);
  jacobian(2, 0) = 0.5;   // joint 0: 0.5 N m per N along z
  jacobian(0, 1) = 0.25;  // joint 1: 0.25 N m per N along x
  JointVector limit(2);
  limit << 10.0, 10.0;
  Vector6d wrench = Vector6d::Zero();
  wrench[0] = 20.0;  // joint 1: 5 N m, half its limit
  wrench[2] = 60.0;  // joint 0: 30 N m, three times its limit
  const EffortRatio ratio = effortRatio(jacobian, wrench, limit, 2);
  EXPECT_DOUBLE_EQ(ratio.ratio, 3.0);
  EXPECT_EQ(ratio.joint, 0);
  EXPECT_DOUBLE_EQ(boundWrench(jacobian, wrench.data(), limit, 2), 3.0);
  EXPECT_DOUBLE_EQ(wrench[2], 20.0) << "scaled along its direction";
  EXPECT_DOUBLE_EQ(wrench[0], 20.0 / 3.0);
  EXPECT_DOUBLE_EQ(effortRatio(jacobian, wrench, limit, 2).ratio, 1.0);
  Vector6d within = Vector6d::Zero();
  within[2] = 10.0;
  EXPECT_DOUBLE_EQ(boundWrench(jacobian, within.data(), limit, 2), 0.5);
  EXPECT_DOUBLE_EQ(within[2], 10.0) << "within the bound: untouched";
}

}  // namespace
}  // namespace comply::pipeline::test
