#pragma once
// What one control cycle sends the joint drives. An arm takes one of four kinds of command; the
// same control law and the same command schema serve all four (pipeline/output_stage.hpp):
//
//   torque     effort per joint                  (torque-controlled arms: FR3, iiwa, Rizon)
//   joint_pd   q_d, dq_d, kp, kd, tau_ff         (drives with an onboard PD: "MIT mode")
//   position   q_d (and dq_d as feedforward)     (position-controlled arms: admittance)
//   velocity   dq_d                              (velocity-controlled arms: admittance)
//
// A joint_pd drive applies tau = kp (q_d - q) + kd (dq_d - dq) + tau_ff at its own rate.

#include <cstdint>
#include <string_view>

#include "comply/core/capacity.hpp"
#include "comply/core/enum_names.hpp"

namespace comply {

enum class OutputMode : std::uint8_t { kTorque, kJointPd, kPosition, kVelocity };

/// Every mode, in the order of the enum, by its name in a controller file (`output.mode`) and in
/// messages.
inline constexpr EnumNames<OutputMode, 4> kOutputModeNames{{{OutputMode::kTorque, "torque"},
                                                            {OutputMode::kJointPd, "joint_pd"},
                                                            {OutputMode::kPosition, "position"},
                                                            {OutputMode::kVelocity, "velocity"}}};

constexpr std::string_view toString(OutputMode mode) noexcept {
  return nameIn(kOutputModeNames, mode, "?");
}

/// The admittance modes: the law moves a virtual arm whose motion the drives follow.
constexpr bool isAdmittance(OutputMode mode) noexcept {
  return mode == OutputMode::kPosition || mode == OutputMode::kVelocity;
}

/// One cycle's command to the drives. Each vector is dof() long; what a mode does not use is
/// left as it was.
struct ActuatorCommand {
  OutputMode mode = OutputMode::kTorque;
  /// torque: the joint torque [N m | N]. joint_pd: tau_ff. position, velocity: the torque that
  /// drove the virtual arm this cycle (for logs; the drives do not receive it).
  JointVector effort;
  JointVector position;   ///< joint_pd: q_d; position: the position command [rad | m]
  JointVector velocity;   ///< joint_pd: dq_d; position: its feedforward; velocity: the command
  JointVector stiffness;  ///< joint_pd: kp [N m/rad | N/m]
  JointVector damping;    ///< joint_pd: kd [N m s/rad | N s/m]

  void resize(int dof) {
    effort.setZero(dof);
    position.setZero(dof);
    velocity.setZero(dof);
    stiffness.setZero(dof);
    damping.setZero(dof);
  }
};

}  // namespace comply
