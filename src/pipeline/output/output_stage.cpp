// The output stage's dispatch over the modes; torque mode is the cycle's torque as it is.

#include "comply/pipeline/output_stage.hpp"

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

OutputStage::OutputStage(const ResolvedController& resolved)
    : parameters_(resolved.parameters),
      dof_(resolved.dof),
      cartesian_(resolved.cartesian()),
      arm_(resolved) {}

const JointState& OutputStage::lawState(const JointState& measured) noexcept {
  return isAdmittance(mode()) ? arm_.lawState(measured) : measured;
}

bool OutputStage::write(CycleStatus status, const Controller& controller,
                        const JointState& measured, double period_s,
                        ActuatorCommand& command) noexcept {
  if (status == CycleStatus::kInactive) {
    return false;
  }
  switch (mode()) {
    case OutputMode::kTorque:
      return true;
    case OutputMode::kJointPd:
      splitForJointPd(controller, status == CycleStatus::kFault, measured, command);
      return true;
    case OutputMode::kPosition:
    case OutputMode::kVelocity:
      if (status == CycleStatus::kFault) {
        arm_.hold(measured, command);
      } else {
        arm_.step(controller, measured, period_s, command);
      }
      return true;
  }
  return false;
}

}  // namespace comply::pipeline
