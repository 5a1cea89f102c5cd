// The nullspace target's jump from the measured joints (validation.max_nullspace_jump_rad): a
// Cartesian command that sets the nullspace group is refused as pose_jump when a joint whose
// nullspace spring pulls is sent further than the limit, with the numbers; at the limit it is
// taken. Before, any nullspace target was taken, and a 1.5 rad one drove the joints past their
// speed limit before the stability guard tripped.

#include <gtest/gtest.h>

#include <string>

#include "command_bits.hpp"
#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline::test {
namespace {

constexpr int kDof = 3;

/// A command that sets only the nullspace group: target `target`, stiffness `stiffness`.
CartesianCommand nullspaceCommand(const JointVector& target, const JointVector& stiffness) {
  CartesianCommand command = CartesianCommand::zero(kDof);
  command.stamp_s = 2.0;
  command.fields = CommandField::kNullspace;
  command.nullspace_position = target;
  command.nullspace_stiffness = stiffness;
  command.nullspace_damping = joints({1.0, 1.0, 1.0});
  return command;
}

MeasuredPose measuredAt(const JointVector& position) {
  MeasuredPose measured;
  measured.position = position;
  measured.valid = true;
  return measured;
}

Verdict validate(CartesianCommand command, const MeasuredPose& measured,
                 const ValidationConfig& limits = {}) {
  return validateCommand(command, limits, kDof, measured, 1.0);
}

TEST(NullspaceJump, TheDefaultLimitIsHalfARadian) {
  EXPECT_DOUBLE_EQ(ValidationConfig{}.max_nullspace_jump_rad, 0.5);
}

TEST(NullspaceJump, AJumpBeyondTheLimitIsRefusedWithItsNumbers) {
  const MeasuredPose measured = measuredAt(joints({0.1, -0.2, 0.3}));
  const Verdict verdict =
      validate(nullspaceCommand(joints({0.1, 1.3, 0.3}), joints({10.0, 10.0, 10.0})), measured);
  EXPECT_FALSE(verdict.accepted);
  EXPECT_EQ(verdict.reason, RejectionReason::kPoseJump);
  EXPECT_EQ(verdict.message.rfind("pose_jump: ", 0), 0U) << verdict.message;
  for (const char* fragment : {"nullspace_position is 1.5 rad", "at joint 2", "limit 0.5 rad",
                               "validation.max_nullspace_jump_rad"}) {
    EXPECT_NE(verdict.message.find(fragment), std::string::npos) << verdict.message;
  }
  // Either direction: the infinity norm.
  EXPECT_FALSE(
      validate(nullspaceCommand(joints({-1.4, -0.2, 0.3}), joints({10.0, 10.0, 10.0})), measured)
          .accepted);
}

TEST(NullspaceJump, AJumpAtTheLimitIsTaken) {
  const MeasuredPose measured = measuredAt(joints({0.0, 0.0, 0.0}));
  EXPECT_TRUE(
      validate(nullspaceCommand(joints({0.5, -0.5, 0.25}), joints({10.0, 10.0, 10.0})), measured)
          .accepted);
  const Verdict beyond = validate(
      nullspaceCommand(joints({0.5, -0.5000001, 0.25}), joints({10.0, 10.0, 10.0})), measured);
  EXPECT_EQ(beyond.reason, RejectionReason::kPoseJump) << beyond.message;
  EXPECT_FALSE(beyond.accepted);
}

TEST(NullspaceJump, TheLimitIsAnOption) {
  const MeasuredPose measured = measuredAt(joints({0.0, 0.0, 0.0}));
  ValidationConfig limits;
  limits.max_nullspace_jump_rad = 2.0;
  EXPECT_TRUE(validate(nullspaceCommand(joints({1.5, 0.0, 0.0}), joints({10.0, 10.0, 10.0})),
                       measured, limits)
                  .accepted);
  limits.max_nullspace_jump_rad = 0.1;
  EXPECT_FALSE(validate(nullspaceCommand(joints({0.2, 0.0, 0.0}), joints({10.0, 10.0, 10.0})),
                        measured, limits)
                   .accepted);
}

TEST(NullspaceJump, AJointWithoutANullspaceSpringIsNotLimited) {
  // Its target pulls nothing: joint 1 at 1.5 rad with no stiffness, joint 3 within the limit.
  const MeasuredPose measured = measuredAt(joints({0.0, 0.0, 0.0}));
  EXPECT_TRUE(validate(nullspaceCommand(joints({1.5, 0.0, 0.4}), joints({0.0, 5.0, 5.0})), measured)
                  .accepted);
  EXPECT_FALSE(
      validate(nullspaceCommand(joints({1.5, 0.0, 0.4}), joints({0.1, 5.0, 5.0})), measured)
          .accepted);
}

TEST(NullspaceJump, NotCheckedWithoutTheGroupOrAMeasurement) {
  CartesianCommand far = nullspaceCommand(joints({1.5, 1.5, 1.5}), joints({10.0, 10.0, 10.0}));
  MeasuredPose measured = measuredAt(joints({0.0, 0.0, 0.0}));
  far.fields = CommandField::kStiffness;  // the nullspace group is not sent
  EXPECT_TRUE(validate(far, measured).accepted);
  far.fields = CommandField::kNullspace;
  measured.valid = false;  // before the first measurement
  EXPECT_TRUE(validate(far, measured).accepted);
  measured = measuredAt(JointVector());  // a chunk's later waypoint: no joints to compare with
  EXPECT_TRUE(validate(far, measured).accepted);
}

TEST(NullspaceJump, MergingARefusedJumpLeavesTheCommandInForce) {
  CartesianCommand merged = CartesianCommand::zero(kDof);
  merged.stamp_s = 1.0;
  merged.nullspace_position = joints({0.1, 0.2, 0.3});
  const CartesianCommand before = merged;
  const Verdict verdict =
      validateAndMerge(nullspaceCommand(joints({2.0, 0.2, 0.3}), joints({1.0, 1.0, 1.0})), {}, kDof,
                       measuredAt(joints({0.1, 0.2, 0.3})), merged);
  EXPECT_FALSE(verdict.accepted);
  expectSameBits(merged, before);
}

}  // namespace
}  // namespace comply::pipeline::test
