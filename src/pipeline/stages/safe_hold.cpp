#include "comply/pipeline/safe_hold.hpp"

#include <cmath>

namespace comply::pipeline {

SafeHold::SafeHold(const CycleParameters& parameters, int dof)
    : parameters_(parameters), dof_(dof) {
  gravity_.setZero(dof);
}

void SafeHold::keepGravity(const model::Data& data) noexcept {
  // A robot that compensates gravity itself holds its own weight; adding it here would lift it.
  if (parameters_.hardware_compensates_gravity) {
    gravity_.setZero();
  } else {
    gravity_ = data.gravity.head(dof_);
  }
  if (parameters_.payload_compensation) {
    gravity_ += data.payload_gravity.head(dof_);
  }
}

void SafeHold::torque(const JointState& state, bool frozen, JointVector& torque) const noexcept {
  for (int i = 0; i < dof_; ++i) {
    // A velocity so large that its damping overflows (a broken sensor) damps nothing.
    const double velocity = frozen ? 0.0 : state.velocity[i];
    const double damping = parameters_.fault_damping[i] * velocity;
    torque[i] = gravity_[i] - (std::isfinite(damping) ? damping : 0.0);
  }
}

}  // namespace comply::pipeline
