#pragma once
// The command interfaces of each output mode (docs/output-modes.md), per joint, and the field of
// comply::ActuatorCommand each carries: what a controller claims in a mode and what the MuJoCo
// hardware exports for a plant actuated that way, from one list.
//
//   torque     <joint>/effort
//   joint_pd   <joint>/position (q_d), /velocity (dq_d), /effort (tau_ff), /stiffness (kp),
//              /damping (kd)
//   position   <joint>/position
//   velocity   <joint>/velocity

#include <string>
#include <string_view>
#include <vector>

#include "comply/core/actuator_command.hpp"

namespace comply_ros2_control {

struct CommandInterface {
  const char* kind;
  comply::JointVector comply::ActuatorCommand::*field;
};

inline std::vector<CommandInterface> commandInterfacesOf(comply::OutputMode mode) {
  using comply::ActuatorCommand;
  switch (mode) {
    case comply::OutputMode::kJointPd:
      return {{"position", &ActuatorCommand::position},
              {"velocity", &ActuatorCommand::velocity},
              {"effort", &ActuatorCommand::effort},
              {"stiffness", &ActuatorCommand::stiffness},
              {"damping", &ActuatorCommand::damping}};
    case comply::OutputMode::kPosition:
      return {{"position", &ActuatorCommand::position}};
    case comply::OutputMode::kVelocity:
      return {{"velocity", &ActuatorCommand::velocity}};
    case comply::OutputMode::kTorque:
      break;
  }
  return {{"effort", &ActuatorCommand::effort}};
}

/// The interface kinds of `mode`, as a block lists them: "effort" or "position, velocity, ...".
inline std::string commandKindsOf(comply::OutputMode mode) {
  std::string kinds;
  for (const CommandInterface& interface : commandInterfacesOf(mode)) {
    kinds += (kinds.empty() ? "" : ", ") + std::string(interface.kind);
  }
  return kinds;
}

}  // namespace comply_ros2_control
