#pragma once
// Commands for the simulated plant's drives in tests that drive it without a controller.

#include "comply/core/actuator_command.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::testing {

/// A command in `mode` that keeps the plant where it is now: the measured positions, every other
/// entry zero.
inline ActuatorCommand holdWhereItIs(sim::SimulatedRobot& robot, OutputMode mode) {
  JointState state = JointState::zero(robot.dof());
  robot.read(state);
  ActuatorCommand command;
  command.resize(robot.dof());
  command.mode = mode;
  command.position = state.position;
  return command;
}

}  // namespace comply::testing
