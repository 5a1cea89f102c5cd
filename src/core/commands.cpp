#include "comply/core/commands.hpp"

namespace comply {
namespace {

// Joint-space fields are sized by the arm; every other kind keeps its default.
void sizeForJoints(JointVector& vector, int dof) {
  vector.setZero(dof);
}
template <typename Other>
void sizeForJoints(Other& /*fixed_size*/, int /*dof*/) {}

}  // namespace

#define COMPLY_SIZE_FOR_JOINTS(name, group, kind, type, unit, constraint, role, init, doc) \
  sizeForJoints(command.name, dof);

JointCommand JointCommand::zero(int dof) {
  JointCommand command;
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_SIZE_FOR_JOINTS)
  return command;
}

CartesianCommand CartesianCommand::zero(int dof) {
  CartesianCommand command;
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_SIZE_FOR_JOINTS)
  return command;
}

#undef COMPLY_SIZE_FOR_JOINTS

}  // namespace comply
