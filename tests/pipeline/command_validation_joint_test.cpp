// Validation and merging of joint commands. Every rejection must keep the last accepted command
// bit for bit and say which field failed, since that message is what the sender gets back.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "command_bits.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "validation_fixture.hpp"

namespace comply::pipeline::test {
namespace {

/// The command in force before each test (stamp 1 s), distinct values in every group.
JointCommand lastAccepted() {
  JointCommand command = JointCommand::zero(kDof);
  command.stamp_s = 1.0;
  command.position = joints({0.1, -0.2, 0.3});
  command.velocity = joints({0.01, 0.02, 0.03});
  command.acceleration = joints({0.5, 0.6, 0.7});
  command.stiffness = joints({100.0, 200.0, 300.0});
  command.damping = joints({10.0, 20.0, 30.0});
  command.torque_feedforward = joints({0.5, -0.5, 1.0});
  return command;
}

/// A valid successor: every group changed, position within the jump limit.
JointCommand nextCommand() {
  JointCommand command = JointCommand::zero(kDof);
  command.stamp_s = 2.0;
  command.position = joints({0.2, -0.1, 0.4});
  command.velocity = joints({-0.01, -0.02, -0.03});
  command.acceleration = joints({1.5, 1.6, 1.7});
  command.stiffness = joints({150.0, 250.0, 0.0});
  command.damping = joints({15.0, 25.0, 0.0});
  command.torque_feedforward = joints({-2.0, 2.0, 0.0});
  return command;
}

MeasuredPose measuredAt(const JointVector& q) {
  MeasuredPose measured;
  measured.position = q;
  measured.valid = true;
  return measured;
}

/// The joint-space groups, each with its bit in the mask and its name in messages.
struct Group {
  CommandField field;
  JointVector JointCommand::*member;
  std::string name;
};

const std::vector<Group>& allGroups() {
  static const std::vector<Group> groups{
      {CommandField::kPosition, &JointCommand::position, "position"},
      {CommandField::kVelocity, &JointCommand::velocity, "velocity"},
      {CommandField::kAcceleration, &JointCommand::acceleration, "acceleration"},
      {CommandField::kStiffness, &JointCommand::stiffness, "stiffness"},
      {CommandField::kDamping, &JointCommand::damping, "damping"},
      {CommandField::kTorqueFeedforward, &JointCommand::torque_feedforward, "torque_feedforward"},
  };
  return groups;
}

class JointValidation : public test::ValidationFixture<JointCommand> {
 protected:
  JointValidation()
      : ValidationFixture(kDof, lastAccepted(), measuredAt(lastAccepted().position), &nextCommand) {
  }
};

TEST_F(JointValidation, AcceptsAndReplacesEveryGroup) {
  const JointCommand incoming = nextCommand();
  const Verdict verdict = validate(incoming);
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  EXPECT_TRUE(verdict.message.empty());
  expectSameBits(merged_, incoming);
}

TEST_F(JointValidation, PartialUpdateKeepsTheOtherGroupsInForce) {
  JointCommand incoming = nextCommand();
  incoming.fields = CommandField::kStiffness;
  // Groups not in the mask are neither validated nor copied: garbage there is harmless.
  incoming.position = joints({kNaN});
  incoming.damping = joints({-1.0, -1.0, -1.0});
  ASSERT_TRUE(validate(incoming).accepted);

  JointCommand expected = lastAccepted();
  expected.stamp_s = 2.0;
  expected.stiffness = incoming.stiffness;
  expectSameBits(merged_, expected);  // includes fields == kAll: the merge is complete
}

TEST_F(JointValidation, EveryGroupAloneReplacesOnlyItself) {
  for (const Group& group : allGroups()) {
    merged_ = lastAccepted();
    JointCommand incoming = nextCommand();
    incoming.fields = group.field;
    ASSERT_TRUE(validate(incoming).accepted) << group.name;
    JointCommand expected = lastAccepted();
    expected.stamp_s = 2.0;
    expected.*group.member = incoming.*group.member;
    SCOPED_TRACE(group.name);
    expectSameBits(merged_, expected);
  }
}

TEST_F(JointValidation, MergedCommandAlwaysCarriesEveryGroup) {
  expectMergedCarriesEveryGroup();
}

TEST_F(JointValidation, RejectsNonFiniteStamp) {
  JointCommand incoming = nextCommand();
  incoming.stamp_s = kNaN;
  expectRejected(incoming, RejectionReason::kNonFinite, {"stamp"});
}

TEST_F(JointValidation, RejectsNonFiniteValueInEveryGroup) {
  for (const Group& group : allGroups()) {
    for (const double bad : {kNaN, kInf, -kInf}) {
      JointCommand incoming = nextCommand();
      (incoming.*group.member)[1] = bad;
      SCOPED_TRACE(group.name);
      expectRejected(incoming, RejectionReason::kNonFinite, {group.name + " holds NaN"});
    }
  }
}

TEST_F(JointValidation, RejectsWrongSizeInEveryGroup) {
  for (const Group& group : allGroups()) {
    JointCommand incoming = nextCommand();
    (incoming.*group.member).conservativeResize(2);
    SCOPED_TRACE(group.name);
    expectRejected(incoming, RejectionReason::kDofMismatch,
                   {group.name + " has 2 entries", "has 3 joints"});
  }
}

TEST_F(JointValidation, RejectsNegativeStiffness) {
  JointCommand incoming = nextCommand();
  incoming.stiffness[2] = -1e-12;
  expectRejected(incoming, RejectionReason::kInvalidGains, {"stiffness", ">= 0"});
}

TEST_F(JointValidation, RejectsNegativeDamping) {
  JointCommand incoming = nextCommand();
  incoming.fields = CommandField::kDamping;
  incoming.damping[0] = -5.0;
  expectRejected(incoming, RejectionReason::kInvalidGains, {"damping", ">= 0"});
}

TEST_F(JointValidation, RejectsRatesAndFeedforwardBeyondAnyArm) {
  JointCommand incoming = nextCommand();
  incoming.velocity[1] = -150.0;
  expectRejected(incoming, RejectionReason::kOutOfRange, {"velocity", "limit of 100"});
  incoming = nextCommand();
  incoming.fields = CommandField::kTorqueFeedforward;
  incoming.torque_feedforward[0] = 1e9;
  expectRejected(incoming, RejectionReason::kOutOfRange, {"torque_feedforward", "limit of 10000"});
}

TEST_F(JointValidation, RejectsStaleStampButAcceptsAnEqualOne) {
  JointCommand incoming = nextCommand();
  incoming.stamp_s = 0.999;
  expectRejected(incoming, RejectionReason::kStaleStamp, {"older"});

  incoming.stamp_s = 1.0;  // resending at the same time is not going backwards
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(JointValidation, RejectsAJumpOfOneJointBeyondTheLimit) {
  JointCommand incoming = nextCommand();
  incoming.position = measured_.position + joints({0.0, 0.6, 0.0});
  expectRejected(incoming, RejectionReason::kPoseJump, {"0.6 rad", "limit 0.5 rad"});
}

TEST_F(JointValidation, AJumpJustBeyondTheLimitIsPrintedApartFromIt) {
  // The second joint measured at 0: its target is the jump itself.
  measured_.position[1] = 0.0;
  JointCommand incoming = nextCommand();
  incoming.position = measured_.position;
  incoming.position[1] = std::nextafter(0.5, 1.0);
  expectRejected(incoming, RejectionReason::kPoseJump,
                 {"target is 0.5000000000000001 rad from the measured position (limit 0.5 rad)"});
}

TEST_F(JointValidation, JumpIsTheLargestJointNotTheNorm) {
  // 0.45 on every joint: norm 0.78 but no joint moves more than the 0.5 rad limit.
  JointCommand incoming = nextCommand();
  incoming.position = measured_.position + joints({0.45, -0.45, 0.45});
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(JointValidation, JumpIsNotCheckedBeforeTheFirstMeasurement) {
  measured_.valid = false;
  JointCommand incoming = nextCommand();
  incoming.position = measured_.position + joints({3.0, 0.0, 0.0});
  ASSERT_TRUE(validate(incoming).accepted);
  EXPECT_EQ(merged_.position, incoming.position);
}

TEST_F(JointValidation, JumpIsNotCheckedWhenThePositionIsNotSent) {
  // The arm was pushed far from the target in force; a gains update must still go through.
  measured_.position = lastAccepted().position + joints({2.0, 2.0, 2.0});
  JointCommand incoming = nextCommand();
  incoming.fields = CommandField::kStiffness | CommandField::kDamping;
  EXPECT_TRUE(validate(incoming).accepted);
}

TEST_F(JointValidation, LateRejectionLeavesNoPartialMerge) {
  // Every group is valid except the position jump, found last: nothing may leak into merged.
  JointCommand incoming = nextCommand();
  incoming.position[0] += 1.0;
  expectRejected(incoming, RejectionReason::kPoseJump, {"measured position"});
}

TEST(RejectionReasonNames, AreDistinctAndStable) {
  EXPECT_EQ(toString(RejectionReason::kNonFinite), "non_finite");
  EXPECT_EQ(toString(RejectionReason::kInvalidQuaternion), "invalid_quaternion");
  EXPECT_EQ(toString(RejectionReason::kInvalidGains), "invalid_gains");
  EXPECT_EQ(toString(RejectionReason::kDofMismatch), "dof_mismatch");
  EXPECT_EQ(toString(RejectionReason::kStaleStamp), "stale_stamp");
  EXPECT_EQ(toString(RejectionReason::kPoseJump), "pose_jump");
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < kRejectionReasonCount; ++i) {
    names.insert(toString(static_cast<RejectionReason>(i)));
  }
  EXPECT_EQ(names.size(), kRejectionReasonCount);
  EXPECT_EQ(names.count("unknown"), 0U);
}

}  // namespace
}  // namespace comply::pipeline::test
