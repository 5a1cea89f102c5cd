// Command intake through the wrappers: an accepted command drives the next cycle; a rejected one
// changes nothing (same torque, same command in force) and is counted under its reason; a partial
// command updates only the field groups it sets.

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "command_bits.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTolerance = 1e-9;

/// The rate limit is lifted so that one cycle shows the law's full response to a command.
const std::string kUnshaped = "torque_rate_limit_nm_per_s: " + std::to_string(kNoRateLimit);

template <typename WrapperType>
class SubmitFixture : public ::testing::Test {
 public:  // read by expectRejectedWithoutEffect
  explicit SubmitFixture(const std::string& plugin, const std::string& lines = kUnshaped)
      : wrapper(fr3Config(plugin, lines)) {}

  void SetUp() override {
    state = restingAt(wrapper.controller(), home);
    wrapper.activate(state);
  }

  /// One cycle at the current state; the law's share of the torque (output minus gravity).
  JointVector lawTorque() {
    EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    return torque.values - state.effort;
  }

  WrapperType wrapper;
  const JointVector home = fr3Home();
  JointState state;
  TorqueBuffer torque;
};

struct Rejection {
  std::string name;
  RejectionReason reason;
};

/// Submits `command`, expects it rejected for `expected.reason`, and checks that nothing changed:
/// command in force (bit for bit), torque of the next cycle (bit for bit), counters.
template <typename WrapperType, typename Command>
void expectRejectedWithoutEffect(SubmitFixture<WrapperType>& fixture, const Command& command,
                                 const Rejection& expected, const JointVector& torque_in_force) {
  SCOPED_TRACE(expected.name);
  const DiagnosticsSnapshot before = fixture.wrapper.diagnostics();
  const Command in_force = fixture.wrapper.lastAccepted();

  const Verdict verdict = fixture.wrapper.submit(command);
  EXPECT_FALSE(verdict.accepted);
  EXPECT_EQ(verdict.reason, expected.reason) << verdict.message;

  const DiagnosticsSnapshot after = fixture.wrapper.diagnostics();
  const auto reason = static_cast<std::size_t>(expected.reason);
  EXPECT_EQ(after.rejections[reason], before.rejections[reason] + 1);
  EXPECT_EQ(after.rejectionsTotal(), before.rejectionsTotal() + 1);
  EXPECT_EQ(after.commands_accepted, before.commands_accepted);
  EXPECT_NE(after.last_error.find(std::string(toString(expected.reason))), std::string::npos)
      << after.last_error;

  expectSameBits(fixture.wrapper.lastAccepted(), in_force);
  const JointVector law = fixture.lawTorque();
  EXPECT_TRUE(sameBits(law, torque_in_force)) << law.transpose() << "\n"
                                              << torque_in_force.transpose();
}

// ---- joint wrapper ----------------------------------------------------------------------------

class JointWrapperSubmit : public SubmitFixture<JointWrapper> {
 protected:
  JointWrapperSubmit() : SubmitFixture(kJointImpedancePlugin) {}

  JointCommand positionTarget(double stamp_s, const JointVector& position) const {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kPosition;
    command.position = position;
    return command;
  }
  JointCommand stiffness(double stamp_s, double value) const {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kStiffness;
    command.stiffness.setConstant(value);
    return command;
  }
};

TEST_F(JointWrapperSubmit, AcceptedCommandDrivesTheNextCycle) {
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), JointVector::Zero(kFr3Dof), kTolerance);

  const Verdict verdict = wrapper.submit(positionTarget(1.0, offset(home, 0, 0.05)));
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  EXPECT_EQ(wrapper.diagnostics().commands_accepted, 1U);

  // Default joint stiffness 100 N m/rad times 0.05 rad on joint 1 only.
  const JointVector expected = offset(JointVector::Zero(kFr3Dof), 0, 100.0 * 0.05);
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), expected, kTolerance);
}

TEST_F(JointWrapperSubmit, RejectedCommandsLeaveThePreviousInForceAndAreCounted) {
  ASSERT_TRUE(wrapper.submit(positionTarget(1.0, offset(home, 0, 0.05))).accepted);
  const JointVector in_force = lawTorque();
  ASSERT_GT(in_force.cwiseAbs().maxCoeff(), 1.0);  // a command that visibly acts

  expectRejectedWithoutEffect(*this, positionTarget(2.0, offset(home, 2, kNaN)),
                              {"NaN position", RejectionReason::kNonFinite}, in_force);
  expectRejectedWithoutEffect(*this, positionTarget(0.5, offset(home, 0, 0.02)),
                              {"stale stamp", RejectionReason::kStaleStamp}, in_force);
  expectRejectedWithoutEffect(*this, positionTarget(2.0, offset(home, 0, 0.8)),
                              {"0.8 rad jump", RejectionReason::kPoseJump}, in_force);
  expectRejectedWithoutEffect(*this, positionTarget(2.0, home.head(kFr3Dof - 1)),
                              {"6 positions for 7 joints", RejectionReason::kDofMismatch},
                              in_force);
  expectRejectedWithoutEffect(*this, stiffness(2.0, -50.0),
                              {"negative stiffness", RejectionReason::kInvalidGains}, in_force);
}

TEST_F(JointWrapperSubmit, GainsOnlyCommandKeepsTheReference) {
  ASSERT_TRUE(wrapper.submit(positionTarget(1.0, offset(home, 0, 0.05))).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), offset(JointVector::Zero(kFr3Dof), 0, 5.0), kTolerance);

  ASSERT_TRUE(wrapper.submit(stiffness(2.0, 200.0)).accepted);
  // Same 0.05 rad error, twice the stiffness.
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), offset(JointVector::Zero(kFr3Dof), 0, 10.0), kTolerance);
  COMPLY_EXPECT_JOINTS_NEAR(wrapper.lastAccepted().position, offset(home, 0, 0.05), 0.0);
}

TEST_F(JointWrapperSubmit, ReactivationKeepsTheGainsInForce) {
  ASSERT_TRUE(wrapper.submit(stiffness(1.0, 300.0)).accepted);
  wrapper.deactivate();
  state = restingAt(wrapper.controller(), offset(home, 1, 0.1));
  wrapper.activate(state);
  EXPECT_EQ(wrapper.lastAccepted().stiffness, JointVector(JointVector::Constant(kFr3Dof, 300.0)));

  // A target 0.01 rad away now pulls with the streamed stiffness, not the configured 100.
  ASSERT_TRUE(wrapper.submit(positionTarget(2.0, offset(state.position, 6, 0.01))).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), offset(JointVector::Zero(kFr3Dof), 6, 3.0), kTolerance);
}

// ---- the intake queue: every command between two cycles applied in order; a sender faster than
// the cycle refused with queue_full instead of overwriting accepted commands
// -----------------------

TEST_F(JointWrapperSubmit, EveryCommandBetweenTwoCyclesIsAppliedInOrder) {
  JointCommand damping = JointCommand::zero(kFr3Dof);
  damping.stamp_s = 1.0;
  damping.fields = CommandField::kDamping;
  damping.damping.setConstant(7.0);
  ASSERT_TRUE(wrapper.submit(damping).accepted);
  ASSERT_TRUE(wrapper.submit(stiffness(2.0, 150.0)).accepted);
  ASSERT_TRUE(wrapper.submit(stiffness(3.0, 160.0)).accepted);
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  const JointCommand in_force = wrapper.lastAccepted();
  EXPECT_EQ(in_force.damping, JointVector(JointVector::Constant(kFr3Dof, 7.0)));
  EXPECT_EQ(in_force.stiffness, JointVector(JointVector::Constant(kFr3Dof, 160.0)));
  EXPECT_EQ(in_force.stamp_s, 3.0);
}

TEST_F(JointWrapperSubmit, ASenderFasterThanTheCycleIsRefusedWithQueueFull) {
  const auto capacity = static_cast<int>(Controller::kIntakeCapacity);
  for (int i = 0; i < capacity; ++i) {
    ASSERT_TRUE(wrapper.submit(stiffness(1.0 + i, 100.0 + i)).accepted) << i;
  }
  const Verdict refused = wrapper.submit(stiffness(1000.0, 999.0));
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.reason, RejectionReason::kQueueFull);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.rejections[static_cast<std::size_t>(RejectionReason::kQueueFull)], 1U);
  EXPECT_EQ(diagnostics.commands_accepted, static_cast<std::uint64_t>(capacity));

  // The cycle applies the accepted ones (the last accepted is in force, not the refused one) and
  // the queue takes commands again.
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_EQ(wrapper.lastAccepted().stiffness[0], 100.0 + capacity - 1);
  // The refused command's stamp was not taken: an older stamp than it is still accepted.
  EXPECT_TRUE(wrapper.submit(stiffness(capacity + 1.0, 321.0)).accepted);
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_EQ(wrapper.lastAccepted().stiffness[0], 321.0);
}

// ---- Cartesian wrapper ------------------------------------------------------------------------

class CartesianWrapperSubmit : public SubmitFixture<CartesianWrapper> {
 protected:
  CartesianWrapperSubmit() : SubmitFixture(kCartesianImpedancePlugin) {}

  void SetUp() override {
    SubmitFixture::SetUp();
    seeded = wrapper.lastAccepted();  // the measured TCP pose after activation
  }

  CartesianCommand poseTarget(double stamp_s, const Eigen::Vector3d& shift) const {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kPosition;
    command.position = seeded.position + shift;
    command.orientation = seeded.orientation;
    return command;
  }
  CartesianCommand stiffness(double stamp_s, const Eigen::Matrix3d& translational) const {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kStiffness;
    command.stiffness_translational = translational;
    command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
    return command;
  }

  CartesianCommand seeded;
};

TEST_F(CartesianWrapperSubmit, AcceptedCommandDrivesTheNextCycle) {
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), JointVector::Zero(kFr3Dof), kTolerance);
  ASSERT_TRUE(wrapper.submit(poseTarget(1.0, {0.02, 0.0, 0.0})).accepted);

  // At rest, only the spring acts: tau = J^T K (p_d - p) with the default K = 500 N/m.
  const Jacobian& jacobian = wrapper.controller().modelData().jacobian;
  Vector6d wrench = Vector6d::Zero();
  wrench[0] = 500.0 * 0.02;
  const JointVector law = lawTorque();
  COMPLY_EXPECT_JOINTS_NEAR(law, JointVector(jacobian.transpose() * wrench), 1e-6);
}

TEST_F(CartesianWrapperSubmit, RejectedCommandsLeaveThePreviousInForceAndAreCounted) {
  ASSERT_TRUE(wrapper.submit(poseTarget(1.0, {0.02, 0.0, -0.01})).accepted);
  const JointVector in_force = lawTorque();
  ASSERT_GT(in_force.cwiseAbs().maxCoeff(), 1.0);

  expectRejectedWithoutEffect(*this, poseTarget(2.0, {kNaN, 0.0, 0.0}),
                              {"NaN position", RejectionReason::kNonFinite}, in_force);
  expectRejectedWithoutEffect(*this, poseTarget(0.5, {0.01, 0.0, 0.0}),
                              {"stale stamp", RejectionReason::kStaleStamp}, in_force);
  expectRejectedWithoutEffect(*this, poseTarget(2.0, {0.3, 0.0, 0.0}),
                              {"0.3 m jump", RejectionReason::kPoseJump}, in_force);

  CartesianCommand short_nullspace = CartesianCommand::zero(kFr3Dof - 1);
  short_nullspace.stamp_s = 2.0;
  short_nullspace.fields = CommandField::kNullspace;
  expectRejectedWithoutEffect(*this, short_nullspace,
                              {"6-joint nullspace", RejectionReason::kDofMismatch}, in_force);

  CartesianCommand scaled = poseTarget(2.0, {0.01, 0.0, 0.0});
  scaled.orientation.coeffs() *= 1.5;
  expectRejectedWithoutEffect(
      *this, scaled, {"quaternion of norm 1.5", RejectionReason::kInvalidQuaternion}, in_force);

  Eigen::Matrix3d skew = 500.0 * Eigen::Matrix3d::Identity();
  skew(0, 1) = 200.0;  // not symmetric
  expectRejectedWithoutEffect(*this, stiffness(2.0, skew),
                              {"asymmetric stiffness", RejectionReason::kInvalidGains}, in_force);
}

TEST_F(CartesianWrapperSubmit, StiffnessOnlyCommandKeepsTheReference) {
  ASSERT_TRUE(wrapper.submit(poseTarget(1.0, {0.02, -0.01, 0.01})).accepted);
  const JointVector first = lawTorque();
  ASSERT_GT(first.cwiseAbs().maxCoeff(), 1.0);

  ASSERT_TRUE(wrapper.submit(stiffness(2.0, 1000.0 * Eigen::Matrix3d::Identity())).accepted);
  // At rest the law is linear in K for a fixed pose error: double K, double torque.
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), JointVector(2.0 * first), 1e-6);
  EXPECT_TRUE(wrapper.lastAccepted().position.isApprox(
      seeded.position + Eigen::Vector3d(0.02, -0.01, 0.01), 1e-15));
}

}  // namespace
}  // namespace comply::pipeline::test
