// Every operation derived from the schema tables, for both command kinds: bus round trips, merge
// by field mask, the reference rules and the field checks (each naming its field).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "comply/schema/json.hpp"
#include "comply/schema/schema.hpp"
#include "schema_support.hpp"

namespace comply::schema {
namespace {

using test::distinctCartesian;
using test::distinctJoint;
using test::kDof;
using test::ramp;
using test::sameBytes;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

MeasuredPose measured() {
  MeasuredPose pose;
  pose.position = ramp(-0.5);
  pose.tcp_position = {0.4, 0.0, 0.6};
  pose.tcp_orientation = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
  pose.valid = true;
  return pose;
}

TEST(SchemaBus, CartesianRoundTripIsExact) {
  const CartesianCommand command = distinctCartesian();
  const comply_cartesian_command bus = toBus(command, kDof);
  EXPECT_EQ(bus.orientation[3], command.orientation.w());  // x y z w
  EXPECT_EQ(bus.stiffness_translational[1], command.stiffness_translational(0, 1));
  EXPECT_EQ(bus.torque_feedforward[kDof], 0.0);  // zero past dof
  const CartesianCommand back = fromBus(bus);
  EXPECT_EQ(toJson(back).dump(), toJson(command).dump());
  EXPECT_TRUE(sameBytes(toBus(back, kDof), bus));
}

TEST(SchemaBus, JointRoundTripIsExact) {
  const JointCommand command = distinctJoint();
  const comply_joint_command bus = toBus(command, kDof);
  EXPECT_EQ(bus.dof, kDof);
  EXPECT_EQ(bus.stiffness[2], command.stiffness[2]);
  const JointCommand back = fromBus(bus);
  EXPECT_EQ(toJson(back).dump(), toJson(command).dump());
  EXPECT_TRUE(sameBytes(toBus(back, kDof), bus));
}

TEST(SchemaMerge, BusTakesOnlyTheGroupsSetAndTheStamp) {
  comply_cartesian_command into = toBus(CartesianCommand::zero(kDof), kDof);
  into.fields = COMPLY_FIELD_POSITION;
  comply_cartesian_command incoming = toBus(distinctCartesian(), kDof);
  incoming.fields = COMPLY_FIELD_STIFFNESS | COMPLY_FIELD_NULLSPACE;
  mergeBus(into, incoming);
  EXPECT_EQ(into.stamp_s, incoming.stamp_s);
  EXPECT_EQ(into.fields, COMPLY_FIELD_POSITION | COMPLY_FIELD_STIFFNESS | COMPLY_FIELD_NULLSPACE);
  EXPECT_EQ(into.stiffness_rotational[4], incoming.stiffness_rotational[4]);
  EXPECT_EQ(into.nullspace_damping[2], incoming.nullspace_damping[2]);
  EXPECT_EQ(into.position[0], 0.0);
  EXPECT_EQ(into.damping_translational[0], 0.0);
  EXPECT_EQ(into.damping_mode, COMPLY_DAMPING_ABSOLUTE);
}

TEST(SchemaMerge, CommandsMergeLikeTheirBuses) {
  for (const CommandField group : {CommandField::kPosition, CommandField::kDamping,
                                   CommandField::kTaskFrame | CommandField::kVelocity}) {
    CartesianCommand into = CartesianCommand::zero(kDof);
    CartesianCommand incoming = distinctCartesian();
    incoming.fields = group;
    comply_cartesian_command bus_into = toBus(into, kDof);
    mergeBus(bus_into, toBus(incoming, kDof));
    merge(into, incoming);
    EXPECT_TRUE(sameBytes(toBus(into, kDof), bus_into));
  }
  JointCommand joint = JointCommand::zero(kDof);
  JointCommand incoming = distinctJoint();
  incoming.fields = CommandField::kDamping;
  merge(joint, incoming);
  EXPECT_EQ(joint.damping, incoming.damping);
  EXPECT_EQ(joint.stiffness, JointVector::Zero(kDof));
}

TEST(SchemaMerge, AssignCopiesOnlyTheGivenKeys) {
  CartesianCommand into = CartesianCommand::zero(kDof);
  const CartesianCommand from = distinctCartesian();
  assign(into, from, FieldSet{1} << 4);  // stiffness_translational, fifth row
  EXPECT_EQ(into.stiffness_translational, from.stiffness_translational);
  EXPECT_EQ(into.stiffness_rotational, Eigen::Matrix3d::Zero());
  EXPECT_EQ(into.stamp_s, 0.0);
}

TEST(SchemaReference, SeedAndStopOnTheCartesianBus) {
  comply_cartesian_command bus = toBus(distinctCartesian(), kDof);
  const MeasuredPose pose = measured();
  seedReference(bus, pose);
  EXPECT_EQ(bus.position[2], 0.6);
  EXPECT_EQ(bus.orientation[0], 1.0);
  EXPECT_EQ(bus.orientation[3], 0.0);
  EXPECT_EQ(bus.nullspace_position[1], pose.position[1]);
  EXPECT_EQ(bus.twist[5], 0.0);
  EXPECT_EQ(bus.acceleration[0], 0.0);
  EXPECT_EQ(bus.stiffness_translational[0], 400.0);  // gains untouched

  bus = toBus(distinctCartesian(), kDof);
  stopMotion(bus);
  EXPECT_EQ(bus.twist[0], 0.0);
  EXPECT_EQ(bus.acceleration[5], 0.0);
  EXPECT_EQ(bus.position[0], 0.1);  // the pose is held
}

TEST(SchemaReference, CommandsFollowTheBusRules) {
  const MeasuredPose pose = measured();
  CartesianCommand cartesian = distinctCartesian();
  comply_cartesian_command cartesian_bus = toBus(cartesian, kDof);
  seedReference(cartesian, pose);
  seedReference(cartesian_bus, pose);
  EXPECT_TRUE(sameBytes(toBus(cartesian, kDof), cartesian_bus));

  JointCommand joint = distinctJoint();
  comply_joint_command joint_bus = toBus(joint, kDof);
  seedReference(joint, pose);
  seedReference(joint_bus, pose);
  EXPECT_EQ(joint.position, pose.position);
  EXPECT_EQ(joint.velocity, JointVector::Zero(kDof));
  EXPECT_TRUE(sameBytes(toBus(joint, kDof), joint_bus));

  joint = distinctJoint();
  joint_bus = toBus(joint, kDof);
  stopMotion(joint);
  stopMotion(joint_bus);
  EXPECT_EQ(joint.acceleration, JointVector::Zero(kDof));
  EXPECT_EQ(joint.position, distinctJoint().position);
  EXPECT_TRUE(sameBytes(toBus(joint, kDof), joint_bus));
}

/// Expects checkFields to fail with `violation`, naming `field`.
template <typename Command, typename Corrupt>
void expectViolation(Command command, Corrupt corrupt, Violation violation,
                     const std::string& field) {
  corrupt(command);
  const CheckResult result = checkFields(command, kDof);
  EXPECT_EQ(result.violation, violation) << result.message;
  EXPECT_EQ(result.field, field);
  EXPECT_EQ(result.message.rfind(field + " ", 0), 0U) << result.message;
}

TEST(SchemaCheck, EachCartesianViolationNamesItsField) {
  const CartesianCommand ok = distinctCartesian();
  CartesianCommand copy = ok;
  EXPECT_TRUE(checkFields(copy, kDof).ok());
  expectViolation(
      ok, [](auto& c) { c.twist[2] = kNaN; }, Violation::kNonFinite, "twist");
  expectViolation(
      ok, [](auto& c) { c.task_frame.coeffs() *= 1.1; }, Violation::kNotUnit, "task_frame");
  expectViolation(
      ok, [](auto& c) { c.damping_rotational(0, 1) = 7.0; }, Violation::kNotSymmetricPsd,
      "damping_rotational");
  expectViolation(
      ok, [](auto& c) { c.damping_ratio[0] = -1.0; }, Violation::kNegative, "damping_ratio");
  expectViolation(
      ok, [](auto& c) { c.nullspace_position = ramp(0.0, 2); }, Violation::kWrongSize,
      "nullspace_position");
  expectViolation(
      ok, [](auto& c) { c.stiffness_translational(2, 2) = 2e6; }, Violation::kGainTooLarge,
      "stiffness_translational");
  expectViolation(
      ok, [](auto& c) { c.damping_ratio[5] = 101.0; }, Violation::kGainTooLarge, "damping_ratio");
  expectViolation(
      ok, [](auto& c) { c.nullspace_damping[0] = 1.5e4; }, Violation::kGainTooLarge,
      "nullspace_damping");
  expectViolation(
      ok, [](auto& c) { c.twist[4] = -1e301; }, Violation::kValueTooLarge, "twist");
  expectViolation(
      ok, [](auto& c) { c.acceleration[0] = 1.5e3; }, Violation::kValueTooLarge, "acceleration");
  expectViolation(
      ok, [](auto& c) { c.wrench_feedforward[2] = 1e9; }, Violation::kValueTooLarge,
      "wrench_feedforward");
  expectViolation(
      ok, [](auto& c) { c.torque_feedforward[2] = -2e4; }, Violation::kValueTooLarge,
      "torque_feedforward");
}

TEST(SchemaCheck, GainLimitsFollowTheUnitAndAdmitTheLimitItself) {
  EXPECT_EQ(gainLimit("N/m"), 1e6);
  EXPECT_EQ(gainLimit("N m s/rad"), 1e4);
  EXPECT_EQ(gainLimit("m"), std::numeric_limits<double>::infinity()) << "not a gain unit";
  CartesianCommand at_limit = distinctCartesian();
  at_limit.stiffness_translational = 1e6 * Eigen::Matrix3d::Identity();
  at_limit.stiffness_rotational = 1e5 * Eigen::Matrix3d::Identity();
  EXPECT_TRUE(checkFields(at_limit, kDof).ok());
  CheckResult over = [&] {
    CartesianCommand copy = at_limit;
    copy.stiffness_rotational(1, 1) = 1.0001e5;
    return checkFields(copy, kDof);
  }();
  EXPECT_EQ(over.violation, Violation::kGainTooLarge);
  EXPECT_NE(over.message.find("above the limit of 100000"), std::string::npos) << over.message;
}

TEST(SchemaCheck, ValueLimitsFollowTheUnitAndAdmitTheLimitItself) {
  EXPECT_EQ(valueLimit("m/s, rad/s"), 100.0);
  EXPECT_EQ(valueLimit("N m | N"), 1e4);
  EXPECT_EQ(valueLimit("m"), std::numeric_limits<double>::infinity()) << "a reach, not a rate";
  EXPECT_EQ(valueLimit("N/m"), std::numeric_limits<double>::infinity()) << "a gain unit";
  CartesianCommand at_limit = distinctCartesian();
  at_limit.twist << 100.0, -100.0, 0.0, 100.0, 0.0, -100.0;
  at_limit.acceleration.setConstant(-1e3);
  at_limit.wrench_feedforward.setConstant(1e4);
  EXPECT_TRUE(checkFields(at_limit, kDof).ok()) << checkFields(at_limit, kDof).message;
  CartesianCommand over = at_limit;
  over.twist[3] = 100.5;
  const CheckResult result = checkFields(over, kDof);
  EXPECT_EQ(result.violation, Violation::kValueTooLarge);
  EXPECT_EQ(
      result.message,
      "twist has an entry of 100.5 m/s, rad/s, above the limit of 100 m/s, rad/s for any arm");
  // Positions have no value limit: their reach is checked against the measured pose.
  CartesianCommand far = distinctCartesian();
  far.position.setConstant(1e300);
  far.nullspace_position.setConstant(1e3);
  EXPECT_TRUE(checkFields(far, kDof).ok());
}

// An entry just above its limit once read "an entry of 1e+06 N/m, above the limit of 1e+06": both
// numbers are printed with as many digits as tell them apart.
TEST(SchemaCheck, LimitMessagesTellTheEntryFromTheLimit) {
  CartesianCommand stiff = distinctCartesian();
  stiff.stiffness_translational = 1e6 * Eigen::Matrix3d::Identity();
  stiff.stiffness_translational(2, 2) = 1000001.0;
  EXPECT_EQ(checkFields(stiff, kDof).message,
            "stiffness_translational has an entry of 1000001 N/m, above the limit of 1000000 N/m "
            "for any arm");
  stiff.stiffness_translational(2, 2) = 1e9;
  EXPECT_EQ(checkFields(stiff, kDof).message,
            "stiffness_translational has an entry of 1000000000 N/m, above the limit of 1000000 "
            "N/m for any arm");
  CartesianCommand fast = distinctCartesian();
  fast.twist[0] = std::nextafter(100.0, 200.0);
  EXPECT_EQ(checkFields(fast, kDof).message,
            "twist has an entry of 100.00000000000001 m/s, rad/s, above the limit of 100 m/s, "
            "rad/s for any arm");
}

TEST(SchemaCheck, EachJointViolationNamesItsField) {
  const JointCommand ok = distinctJoint();
  expectViolation(
      ok, [](auto& c) { c.velocity[0] = kNaN; }, Violation::kNonFinite, "velocity");
  expectViolation(
      ok, [](auto& c) { c.stiffness[1] = -1.0; }, Violation::kNegative, "stiffness");
  expectViolation(
      ok, [](auto& c) { c.stiffness[1] = 1.1e6; }, Violation::kGainTooLarge, "stiffness");
  expectViolation(
      ok, [](auto& c) { c.velocity[1] = 101.0; }, Violation::kValueTooLarge, "velocity");
  expectViolation(
      ok, [](auto& c) { c.acceleration[0] = -1e4; }, Violation::kValueTooLarge, "acceleration");
  expectViolation(
      ok, [](auto& c) { c.torque_feedforward[2] = 1e9; }, Violation::kValueTooLarge,
      "torque_feedforward");
  expectViolation(
      ok, [](auto& c) { c.torque_feedforward = ramp(0.0, 4); }, Violation::kWrongSize,
      "torque_feedforward");
}

TEST(SchemaCheck, OnlyTheGroupsSetAreCheckedAndDriftIsRenormalised) {
  CartesianCommand command = distinctCartesian();
  command.fields = CommandField::kPosition;
  command.twist[0] = kNaN;
  command.orientation.coeffs() *= 1.0005;
  ASSERT_TRUE(checkFields(command, kDof).ok());
  EXPECT_NEAR(command.orientation.norm(), 1.0, 1e-15);
}

}  // namespace
}  // namespace comply::schema
