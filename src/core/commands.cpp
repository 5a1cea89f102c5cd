#include "comply/core/commands.hpp"

namespace comply {

JointCommand JointCommand::zero(int dof) {
  JointCommand command;
  for (JointVector* vector : {&command.position, &command.velocity, &command.acceleration,
                              &command.stiffness, &command.damping, &command.torque_feedforward}) {
    vector->setZero(dof);
  }
  return command;
}

CartesianCommand CartesianCommand::zero(int dof) {
  CartesianCommand command;
  for (JointVector* vector : {&command.torque_feedforward, &command.nullspace_position,
                              &command.nullspace_stiffness, &command.nullspace_damping}) {
    vector->setZero(dof);
  }
  return command;
}

}  // namespace comply
