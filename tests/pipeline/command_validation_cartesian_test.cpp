// Validation and merging of Cartesian commands: unit quaternions (drift renormalised, the rest
// rejected), symmetric PSD gain blocks, joint-space sizes, fresh stamps and bounded pose jumps.
// Every rejection must keep the last accepted command bit for bit and name the failing field.

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "command_bits.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "validation_fixture.hpp"

namespace comply::pipeline::test {
namespace {

Eigen::Quaterniond rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

Eigen::Matrix3d symmetric(double a, double b, double c, double ab, double ac, double bc) {
  Eigen::Matrix3d m;
  m << a, ab, ac, ab, b, bc, ac, bc, c;
  return m;
}

/// The command in force before each test (stamp 1 s), distinct values in every group.
CartesianCommand lastAccepted() {
  CartesianCommand command = CartesianCommand::zero(kDof);
  command.stamp_s = 1.0;
  command.position = {0.4, 0.1, 0.5};
  command.orientation = rotation(0.3, Eigen::Vector3d::UnitZ());
  command.twist << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
  command.acceleration << 1, 2, 3, 4, 5, 6;
  command.stiffness_translational = symmetric(500, 400, 300, 10, 20, 30);
  command.stiffness_rotational = symmetric(30, 20, 10, 1, 2, 3);
  command.damping_translational = symmetric(45, 40, 35, 1, 2, 3);
  command.damping_rotational = symmetric(3, 2, 1, 0.1, 0.2, 0.3);
  command.damping_mode = DampingMode::kAbsolute;
  command.damping_ratio << 0.7, 0.8, 0.9, 1.0, 1.1, 1.2;
  command.task_frame = rotation(0.2, Eigen::Vector3d::UnitX());
  command.wrench_feedforward << -1, -2, -3, -4, -5, -6;
  command.torque_feedforward = joints({0.5, -0.5, 1.0});
  command.nullspace_position = joints({0.1, 0.2, 0.3});
  command.nullspace_stiffness = joints({2.0, 3.0, 4.0});
  command.nullspace_damping = joints({0.5, 0.6, 0.7});
  return command;
}

/// A valid successor: every group changed, the pose within the jump limits of lastAccepted().
CartesianCommand nextCommand() {
  CartesianCommand command = CartesianCommand::zero(kDof);
  command.stamp_s = 2.0;
  command.position = {0.45, 0.08, 0.52};
  command.orientation = rotation(0.5, Eigen::Vector3d::UnitZ());
  command.twist << -0.1, -0.2, -0.3, -0.4, -0.5, -0.6;
  command.acceleration << 6, 5, 4, 3, 2, 1;
  command.stiffness_translational = symmetric(800, 800, 100, 0, 0, 0);
  command.stiffness_rotational = symmetric(50, 50, 5, 4, 0, 0);
  command.damping_translational = Eigen::Matrix3d::Zero();  // PSD includes zero
  command.damping_rotational = symmetric(4, 4, 1, 0, 0, 0);
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio << 1, 1, 1, 0.5, 0.5, 0;
  command.task_frame = rotation(-0.4, Eigen::Vector3d(1, 1, 0));
  command.wrench_feedforward << 6, 5, 4, 3, 2, 1;
  command.torque_feedforward = joints({-1.0, 0.0, 1.0});
  command.nullspace_position = joints({-0.1, -0.2, -0.3});
  command.nullspace_stiffness = joints({0.0, 1.0, 10.0});
  command.nullspace_damping = joints({0.0, 0.1, 1.0});
  return command;
}

MeasuredPose measuredAtLastTarget() {
  MeasuredPose measured;
  measured.tcp_position = lastAccepted().position;
  measured.tcp_orientation = lastAccepted().orientation;
  measured.valid = true;
  return measured;
}

class CartesianValidation : public test::ValidationFixture<CartesianCommand> {
 protected:
  CartesianValidation()
      : ValidationFixture(kDof, lastAccepted(), measuredAtLastTarget(), &nextCommand) {}
};

TEST_F(CartesianValidation, AcceptsAndReplacesEveryGroup) {
  const CartesianCommand incoming = nextCommand();
  const Verdict verdict = validate(incoming);
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  EXPECT_TRUE(verdict.message.empty());
  // Unit quaternions may lose a last bit to the renormalisation; everything else is copied.
  EXPECT_TRUE(merged_.orientation.coeffs().isApprox(incoming.orientation.coeffs(), 1e-15));
  EXPECT_TRUE(merged_.task_frame.coeffs().isApprox(incoming.task_frame.coeffs(), 1e-15));
  CartesianCommand expected = incoming;
  expected.orientation = merged_.orientation;
  expected.task_frame = merged_.task_frame;
  expectSameBits(merged_, expected);
}

TEST_F(CartesianValidation, GainsOnlyUpdateLeavesThePoseInForce) {
  CartesianCommand incoming = nextCommand();
  incoming.fields = CommandField::kStiffness;
  // Groups not in the mask are neither validated nor copied.
  incoming.position.x() = kNaN;
  incoming.orientation.coeffs() *= 3.0;
  incoming.torque_feedforward = joints({1.0});
  ASSERT_TRUE(validate(incoming).accepted);

  CartesianCommand expected = lastAccepted();
  expected.stamp_s = 2.0;
  expected.stiffness_translational = incoming.stiffness_translational;
  expected.stiffness_rotational = incoming.stiffness_rotational;
  expectSameBits(merged_, expected);  // includes fields == kAll: the merge is complete
}

TEST_F(CartesianValidation, DampingGroupCarriesModeAndRatios) {
  CartesianCommand incoming = nextCommand();
  incoming.fields = CommandField::kDamping;
  ASSERT_TRUE(validate(incoming).accepted);

  CartesianCommand expected = lastAccepted();
  expected.stamp_s = 2.0;
  expected.damping_translational = incoming.damping_translational;
  expected.damping_rotational = incoming.damping_rotational;
  expected.damping_mode = DampingMode::kRatio;
  expected.damping_ratio = incoming.damping_ratio;
  expectSameBits(merged_, expected);
}

TEST_F(CartesianValidation, EachRemainingGroupAloneReplacesOnlyItself) {
  struct Case {
    CommandField field;
    std::function<void(CartesianCommand&, const CartesianCommand&)> copy;
    const char* name;
  };
  const std::vector<Case> cases{
      {CommandField::kVelocity, [](auto& e, const auto& in) { e.twist = in.twist; }, "twist"},
      {CommandField::kAcceleration,
       [](auto& e, const auto& in) { e.acceleration = in.acceleration; }, "acceleration"},
      {CommandField::kWrenchFeedforward,
       [](auto& e, const auto& in) { e.wrench_feedforward = in.wrench_feedforward; }, "wrench"},
      {CommandField::kTorqueFeedforward,
       [](auto& e, const auto& in) { e.torque_feedforward = in.torque_feedforward; }, "torque"},
      {CommandField::kNullspace,
       [](auto& e, const auto& in) {
         e.nullspace_position = in.nullspace_position;
         e.nullspace_stiffness = in.nullspace_stiffness;
         e.nullspace_damping = in.nullspace_damping;
       },
       "nullspace"},
  };
  for (const Case& c : cases) {
    merged_ = lastAccepted();
    CartesianCommand incoming = nextCommand();
    incoming.fields = c.field;
    ASSERT_TRUE(validate(incoming).accepted) << c.name;
    CartesianCommand expected = lastAccepted();
    expected.stamp_s = 2.0;
    c.copy(expected, incoming);
    SCOPED_TRACE(c.name);
    expectSameBits(merged_, expected);
  }
}

TEST_F(CartesianValidation, RenormalisesSmallQuaternionDrift) {
  CartesianCommand incoming = nextCommand();
  incoming.orientation.coeffs() *= 1.0 + 5e-4;
  incoming.task_frame.coeffs() *= 1.0 - 5e-4;
  ASSERT_TRUE(validate(incoming).accepted);
  EXPECT_NEAR(merged_.orientation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(merged_.task_frame.norm(), 1.0, 1e-15);
  EXPECT_TRUE(merged_.orientation.coeffs().isApprox(nextCommand().orientation.coeffs(), 1e-15));
  EXPECT_TRUE(merged_.task_frame.coeffs().isApprox(nextCommand().task_frame.coeffs(), 1e-15));
}

TEST_F(CartesianValidation, RejectsOrientationFarFromUnitNorm) {
  expectRejected([](auto& c) { c.orientation.coeffs() *= 1.01; },
                 RejectionReason::kInvalidQuaternion, {"orientation", "norm 1.01"});
  expectRejected([](auto& c) { c.orientation.coeffs().setZero(); },
                 RejectionReason::kInvalidQuaternion, {"orientation", "norm 0"});
}

TEST_F(CartesianValidation, RejectsTaskFrameFarFromUnitNorm) {
  expectRejected([](auto& c) { c.task_frame.coeffs() *= 0.5; }, RejectionReason::kInvalidQuaternion,
                 {"task_frame", "norm 0.5"});
}

TEST_F(CartesianValidation, MergedCommandAlwaysCarriesEveryGroup) {
  expectMergedCarriesEveryGroup();
}

TEST_F(CartesianValidation, RejectsNonFiniteStamp) {
  expectRejected([](auto& c) { c.stamp_s = kNaN; }, RejectionReason::kNonFinite, {"stamp"});
}

TEST_F(CartesianValidation, RejectsNonFiniteValueInEveryField) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, std::function<void(CartesianCommand&)>>> fields{
      {"position", [](auto& c) { c.position.y() = kNaN; }},
      {"orientation", [](auto& c) { c.orientation.w() = kNaN; }},
      {"twist", [](auto& c) { c.twist[5] = kNaN; }},
      {"acceleration", [&](auto& c) { c.acceleration[0] = inf; }},
      {"stiffness_translational", [](auto& c) { c.stiffness_translational(1, 1) = kNaN; }},
      {"stiffness_rotational", [&](auto& c) { c.stiffness_rotational(2, 0) = -inf; }},
      {"damping_translational", [](auto& c) { c.damping_translational(0, 2) = kNaN; }},
      {"damping_rotational", [](auto& c) { c.damping_rotational(1, 2) = kNaN; }},
      {"damping_ratio", [](auto& c) { c.damping_ratio[3] = kNaN; }},
      {"task_frame", [](auto& c) { c.task_frame.x() = kNaN; }},
      {"wrench_feedforward", [&](auto& c) { c.wrench_feedforward[4] = inf; }},
      {"torque_feedforward", [](auto& c) { c.torque_feedforward[2] = kNaN; }},
      {"nullspace_position", [](auto& c) { c.nullspace_position[0] = kNaN; }},
      {"nullspace_stiffness", [](auto& c) { c.nullspace_stiffness[1] = kNaN; }},
      {"nullspace_damping", [&](auto& c) { c.nullspace_damping[2] = inf; }},
  };
  for (const auto& [name, corrupt] : fields) {
    SCOPED_TRACE(name);
    expectRejected(corrupt, RejectionReason::kNonFinite, {name + " holds NaN or infinity"});
  }
}

TEST_F(CartesianValidation, RejectsAsymmetricStiffness) {
  expectRejected([](auto& c) { c.stiffness_translational(0, 1) += 1.0; },
                 RejectionReason::kInvalidGains, {"stiffness", "symmetric"});
}

TEST_F(CartesianValidation, RejectsStiffnessWithANegativeEigenvalue) {
  // Diagonal negative, and symmetric with positive diagonal but eigenvalue 1 - 2 = -1.
  expectRejected([](auto& c) { c.stiffness_rotational = symmetric(1, 1, -1, 0, 0, 0); },
                 RejectionReason::kInvalidGains, {"stiffness", "positive semi-definite"});
  expectRejected([](auto& c) { c.stiffness_translational = symmetric(1, 1, 1, 2, 0, 0); },
                 RejectionReason::kInvalidGains, {"stiffness", "positive semi-definite"});
}

TEST_F(CartesianValidation, AcceptsAsymmetryWithinTheRelativeTolerance) {
  // 1e-7 on entries of 1000 is 1e-10 relative, below the 1e-9 tolerance.
  CartesianCommand incoming = nextCommand();
  incoming.stiffness_translational = 1000.0 * Eigen::Matrix3d::Identity();
  incoming.stiffness_translational(0, 1) = 1e-7;
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(CartesianValidation, RejectsInvalidDampingBlocks) {
  expectRejected([](auto& c) { c.damping_translational(2, 0) = 5.0; },
                 RejectionReason::kInvalidGains, {"damping", "symmetric"});
  expectRejected([](auto& c) { c.damping_rotational = symmetric(1, 1, 1, 0, 0, 3); },
                 RejectionReason::kInvalidGains, {"damping", "positive semi-definite"});
}

TEST_F(CartesianValidation, RejectsNegativeDampingRatio) {
  expectRejected([](auto& c) { c.damping_ratio[4] = -0.1; }, RejectionReason::kInvalidGains,
                 {"damping_ratio", ">= 0"});
}

TEST_F(CartesianValidation, RejectsNegativeNullspaceGains) {
  expectRejected([](auto& c) { c.nullspace_stiffness[0] = -1.0; }, RejectionReason::kInvalidGains,
                 {"nullspace_stiffness", ">= 0"});
  expectRejected([](auto& c) { c.nullspace_damping[2] = -1.0; }, RejectionReason::kInvalidGains,
                 {"nullspace_damping", ">= 0"});
}

TEST_F(CartesianValidation, RejectsRatesAndFeedforwardBeyondAnyArm) {
  // Finite, so no NaN check catches them; held in force they would pin every joint at its limit.
  expectRejected([](auto& c) { c.twist[0] = 1e301; }, RejectionReason::kOutOfRange,
                 {"twist has an entry of 1e+301 m/s, rad/s", "limit of 100"});
  expectRejected([](auto& c) { c.acceleration[5] = -2e3; }, RejectionReason::kOutOfRange,
                 {"acceleration", "limit of 1000"});
  expectRejected([](auto& c) { c.wrench_feedforward[3] = 1e9; }, RejectionReason::kOutOfRange,
                 {"wrench_feedforward", "limit of 10000"});
  expectRejected([](auto& c) { c.torque_feedforward[1] = 1e9; }, RejectionReason::kOutOfRange,
                 {"torque_feedforward", "limit of 10000"});
}

TEST_F(CartesianValidation, RejectsJointSpaceFieldsOfTheWrongSize) {
  expectRejected(
      [](auto& c) {
        c.torque_feedforward = joints({1.0, 2.0});
      },
      RejectionReason::kDofMismatch, {"torque_feedforward", "3 entries"});
  expectRejected(
      [](auto& c) {
        c.nullspace_position = joints({1.0, 2.0, 3.0, 4.0});
      },
      RejectionReason::kDofMismatch, {"nullspace_position", "3 entries"});
  expectRejected([](auto& c) { c.nullspace_stiffness = JointVector(); },
                 RejectionReason::kDofMismatch, {"nullspace_stiffness", "3 entries"});
  expectRejected([](auto& c) { c.nullspace_damping = joints({1.0}); },
                 RejectionReason::kDofMismatch, {"nullspace_damping", "3 entries"});
}

TEST_F(CartesianValidation, RejectsStaleStampButAcceptsAnEqualOne) {
  expectRejected([](auto& c) { c.stamp_s = 0.5; }, RejectionReason::kStaleStamp, {"older"});
  CartesianCommand incoming = nextCommand();
  incoming.stamp_s = 1.0;
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(CartesianValidation, RejectsPositionJump) {
  // 0.12 m along x from the measured TCP, limit 0.1 m; orientation unchanged.
  expectRejected(
      [](auto& c) {
        c.position = lastAccepted().position + Eigen::Vector3d(0.12, 0.0, 0.0);
        c.orientation = lastAccepted().orientation;
      },
      RejectionReason::kPoseJump, {"target is 0.12 m", "limits 0.1 m / 0.6 rad"});
}

TEST_F(CartesianValidation, AJumpJustBeyondTheLimitIsPrintedApartFromIt) {
  // 1 nm beyond the 0.1 m limit along x from the measured TCP: once "target is 0.1 m ... (limits
  // 0.1 m ...)".
  CartesianCommand incoming = nextCommand();
  incoming.position = lastAccepted().position + Eigen::Vector3d(0.1 + 1e-9, 0.0, 0.0);
  incoming.orientation = lastAccepted().orientation;
  const double distance = (incoming.position - lastAccepted().position).norm();
  ASSERT_GT(distance, 0.1) << "the sum must land beyond the limit";
  const Verdict verdict = validate(incoming);
  EXPECT_EQ(verdict.reason, RejectionReason::kPoseJump) << verdict.message;
  EXPECT_NE(verdict.message.find("target is 0.100000001 m / 0 rad"), std::string::npos)
      << verdict.message;
  EXPECT_NE(verdict.message.find("limits 0.1 m / 0.6 rad"), std::string::npos) << verdict.message;
}

TEST_F(CartesianValidation, RejectsOrientationJump) {
  // 0.7 rad about an oblique axis from the measured TCP, limit 0.6 rad; position unchanged.
  expectRejected(
      [](auto& c) {
        c.position = lastAccepted().position;
        c.orientation = lastAccepted().orientation * rotation(0.7, Eigen::Vector3d(1, 2, 3));
      },
      RejectionReason::kPoseJump, {"0 m / 0.7 rad", "measured pose"});
}

TEST_F(CartesianValidation, AcceptsJumpsJustWithinTheLimits) {
  CartesianCommand incoming = nextCommand();
  incoming.position = lastAccepted().position + Eigen::Vector3d(0.0, 0.054, -0.072);  // 0.09 m
  incoming.orientation = lastAccepted().orientation * rotation(0.59, Eigen::Vector3d(0, 1, 1));
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(CartesianValidation, OppositeQuaternionIsTheSameOrientation) {
  // q and -q are the same rotation: no jump, whatever the sign the sender uses.
  CartesianCommand incoming = nextCommand();
  incoming.position = lastAccepted().position;
  incoming.orientation.coeffs() = -lastAccepted().orientation.coeffs();
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(CartesianValidation, JumpIsNotCheckedBeforeTheFirstMeasurement) {
  measured_.valid = false;
  CartesianCommand incoming = nextCommand();
  incoming.position = {2.0, -2.0, 2.0};
  incoming.orientation = rotation(3.0, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(validate(incoming).accepted);
  EXPECT_EQ(merged_.position, incoming.position);
}

TEST_F(CartesianValidation, JumpIsNotCheckedWhenThePoseIsNotSent) {
  // The arm was pushed far from the target in force; a gains update must still go through.
  measured_.tcp_position += Eigen::Vector3d(1.0, 0.0, 0.0);
  CartesianCommand incoming = nextCommand();
  incoming.fields = CommandField::kStiffness | CommandField::kDamping;
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(CartesianValidation, LateRejectionLeavesNoPartialMerge) {
  // Gains, task frame and feedforwards are valid and processed before the jump check fails.
  expectRejected([](auto& c) { c.position.z() += 1.0; }, RejectionReason::kPoseJump,
                 {"measured pose"});
}

TEST_F(CartesianValidation, ValidateCommandChecksAndNormalisesWithoutMerging) {
  CartesianCommand incoming = nextCommand();
  incoming.orientation.coeffs() *= 1.0 + 5e-4;
  const CartesianCommand before = merged_;
  ASSERT_TRUE(validateCommand(incoming, limits_, kDof, measured_, 1.0).accepted);
  EXPECT_NEAR(incoming.orientation.norm(), 1.0, 1e-15);  // in place
  expectSameBits(merged_, before);

  incoming.stamp_s = 0.5;
  EXPECT_EQ(validateCommand(incoming, limits_, kDof, measured_, 1.0).reason,
            RejectionReason::kStaleStamp);
  incoming = nextCommand();
  incoming.position.z() += 1.0;
  EXPECT_EQ(validateCommand(incoming, limits_, kDof, measured_, 1.0).reason,
            RejectionReason::kPoseJump);
}

}  // namespace
}  // namespace comply::pipeline::test
