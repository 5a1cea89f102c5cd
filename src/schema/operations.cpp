// The operations of schema.hpp for the two real schemas: each forwards to the generic machinery.

#include "comply/schema/generic_check.hpp"
#include "schemas.hpp"

namespace comply::schema {

// The C++ enums and the ABI constants are two spellings of the same numbers.
static_assert(static_cast<std::uint32_t>(CommandField::kPosition) == COMPLY_FIELD_POSITION);
static_assert(static_cast<std::uint32_t>(CommandField::kVelocity) == COMPLY_FIELD_VELOCITY);
static_assert(static_cast<std::uint32_t>(CommandField::kAcceleration) == COMPLY_FIELD_ACCELERATION);
static_assert(static_cast<std::uint32_t>(CommandField::kStiffness) == COMPLY_FIELD_STIFFNESS);
static_assert(static_cast<std::uint32_t>(CommandField::kDamping) == COMPLY_FIELD_DAMPING);
static_assert(static_cast<std::uint32_t>(CommandField::kTaskFrame) == COMPLY_FIELD_TASK_FRAME);
static_assert(static_cast<std::uint32_t>(CommandField::kWrenchFeedforward) ==
              COMPLY_FIELD_WRENCH_FEEDFORWARD);
static_assert(static_cast<std::uint32_t>(CommandField::kTorqueFeedforward) ==
              COMPLY_FIELD_TORQUE_FEEDFORWARD);
static_assert(static_cast<std::uint32_t>(CommandField::kNullspace) == COMPLY_FIELD_NULLSPACE);
static_assert(static_cast<std::uint32_t>(CommandField::kForce) == COMPLY_FIELD_FORCE);
static_assert(static_cast<std::uint32_t>(CommandField::kReflex) == COMPLY_FIELD_REFLEX);
static_assert(static_cast<std::uint32_t>(CommandField::kWorkspace) == COMPLY_FIELD_WORKSPACE);
static_assert(static_cast<int>(DampingMode::kAbsolute) == COMPLY_DAMPING_ABSOLUTE);
static_assert(static_cast<int>(DampingMode::kRatio) == COMPLY_DAMPING_RATIO);
static_assert(kMaxDof == COMPLY_MAX_DOF, "core capacity and ABI capacity must agree");

comply_cartesian_command toBus(const CartesianCommand& command, int dof) {
  return generic::toBus<CartesianSchema>(command, dof);
}
comply_joint_command toBus(const JointCommand& command, int dof) {
  return generic::toBus<JointSchema>(command, dof);
}
CartesianCommand fromBus(const comply_cartesian_command& bus) {
  return generic::fromBus<CartesianSchema>(bus);
}
JointCommand fromBus(const comply_joint_command& bus) {
  return generic::fromBus<JointSchema>(bus);
}

void mergeBus(comply_cartesian_command& into, const comply_cartesian_command& incoming) noexcept {
  generic::mergeInto<CartesianSchema, true>(into, incoming);
}
void mergeBus(comply_joint_command& into, const comply_joint_command& incoming) noexcept {
  generic::mergeInto<JointSchema, true>(into, incoming);
}
void merge(CartesianCommand& into, const CartesianCommand& incoming) {
  generic::mergeInto<CartesianSchema, false>(into, incoming);
}
void merge(JointCommand& into, const JointCommand& incoming) {
  generic::mergeInto<JointSchema, false>(into, incoming);
}
void assign(CartesianCommand& into, const CartesianCommand& from, FieldSet keys) {
  generic::assign<CartesianSchema>(into, from, keys);
}
void assign(JointCommand& into, const JointCommand& from, FieldSet keys) {
  generic::assign<JointSchema>(into, from, keys);
}

void seedReference(comply_cartesian_command& bus, const MeasuredPose& measured) noexcept {
  generic::applyRoles<CartesianSchema, true>(bus, &measured, bus.dof);
}
void seedReference(comply_joint_command& bus, const MeasuredPose& measured) noexcept {
  generic::applyRoles<JointSchema, true>(bus, &measured, bus.dof);
}
void seedReference(CartesianCommand& command, const MeasuredPose& measured) {
  generic::applyRoles<CartesianSchema, false>(command, &measured,
                                              static_cast<int>(measured.position.size()));
}
void seedReference(JointCommand& command, const MeasuredPose& measured) {
  generic::applyRoles<JointSchema, false>(command, &measured,
                                          static_cast<int>(measured.position.size()));
}
void stopMotion(comply_cartesian_command& bus) noexcept {
  generic::applyRoles<CartesianSchema, true>(bus, nullptr, bus.dof);
}
void stopMotion(comply_joint_command& bus) noexcept {
  generic::applyRoles<JointSchema, true>(bus, nullptr, bus.dof);
}
void stopMotion(CartesianCommand& command) noexcept {
  generic::applyRoles<CartesianSchema, false>(command, nullptr, -1);
}
void stopMotion(JointCommand& command) noexcept {
  generic::applyRoles<JointSchema, false>(command, nullptr, -1);
}

CheckResult checkFields(CartesianCommand& command, int dof, const CheckOptions& options) {
  return generic::checkFields<CartesianSchema>(command, dof, options);
}
CheckResult checkFields(JointCommand& command, int dof, const CheckOptions& options) {
  return generic::checkFields<JointSchema>(command, dof, options);
}

}  // namespace comply::schema
