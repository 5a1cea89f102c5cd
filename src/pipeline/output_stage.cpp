// The output stage's dispatch over the modes; torque mode is the cycle's torque as it is.

#include "comply/pipeline/output_stage.hpp"

namespace comply::pipeline {

OutputStage::OutputStage(const ResolvedController& resolved)
    : parameters_(resolved.parameters),
      dof_(resolved.dof),
      cartesian_(resolved.cartesian()),
      added_inertia_(
          (resolved.parameters.output.admittance.added_mass_kg.array() > 0.0).any() ||
          (resolved.parameters.output.admittance.added_inertia_kg_m2.array() > 0.0).any()) {
  virtual_ = JointState::zero(dof_);
  last_measured_.setZero(dof_);
  hold_position_.setZero(dof_);
  inertia_.setZero(dof_, dof_);
  virtual_torque_.setZero(dof_);
  acceleration_.setZero(dof_);
}

void OutputStage::activate(const JointState& state) noexcept {
  virtual_.position = state.position;
  virtual_.velocity = state.velocity;
  virtual_.effort.setZero(dof_);
  last_measured_ = state.position;
  acceleration_.setZero(dof_);
  holding_ = false;
}

bool OutputStage::cycle(Controller& controller, const JointState& state, double period_s,
                        ActuatorCommand& command) noexcept {
  command.mode = mode();
  const std::span<double> effort(command.effort.data(),
                                 static_cast<std::size_t>(command.effort.size()));
  switch (mode()) {
    case OutputMode::kTorque:
      return controller.update(state, period_s, effort) != CycleStatus::kInactive;
    case OutputMode::kJointPd: {
      const CycleStatus status = controller.update(state, period_s, effort);
      if (status == CycleStatus::kInactive) {
        return false;
      }
      splitForJointPd(controller, status == CycleStatus::kFault, state, command);
      return true;
    }
    case OutputMode::kPosition:
    case OutputMode::kVelocity:
      return admittance(controller, state, period_s, command);
  }
  return false;
}

}  // namespace comply::pipeline
