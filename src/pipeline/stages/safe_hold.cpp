#include "comply/pipeline/safe_hold.hpp"

#include <algorithm>
#include <cmath>

namespace comply::pipeline {
namespace {

// The holding spring's w_n T on the lightest inertia: stiff enough to keep the stopped pose against
// a model's gravity error, far inside the sampled loop's stability (w_n T < 0.43).
constexpr double kHoldWnPeriod = 0.1;

}  // namespace

SafeHold::SafeHold(const CycleParameters& parameters, int dof)
    : parameters_(parameters), dof_(dof) {
  gravity_.setZero(dof);
  rest_position_.setZero(dof);
}

void SafeHold::reset() noexcept {
  at_rest_ = false;
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

double SafeHold::damping(int joint, double period_s) const noexcept {
  const double inertia =
      parameters_.joint_inertia.size() == dof_ ? parameters_.joint_inertia[joint] : 0.0;
  return std::max(parameters_.fault_damping[joint], inertia / (2.0 * period_s));
}

void SafeHold::torque(const JointState& state, bool frozen, double period_s,
                      JointVector& torque) noexcept {
  if (frozen) {
    torque = gravity_;
    return;
  }
  if (!at_rest_) {
    at_rest_ = (state.velocity.head(dof_).cwiseAbs().array() < kRestSpeed).all();
    rest_position_ = state.position;
  }
  for (int i = 0; i < dof_; ++i) {
    // Beside gravity the effort limit leaves this much to stop the joint with.
    const double available = std::max(parameters_.effort_limit[i] - std::abs(gravity_[i]), 0.0);
    const double gain = damping(i, period_s);
    double brake = gain * state.velocity[i];
    if (at_rest_) {
      const double inertia =
          parameters_.joint_inertia.size() == dof_ ? parameters_.joint_inertia[i] : 0.0;
      const double stiffness = inertia * (kHoldWnPeriod / period_s) * (kHoldWnPeriod / period_s);
      brake -= stiffness * (rest_position_[i] - state.position[i]);
    }
    // A velocity so large that its damping overflows (a broken sensor) brakes nothing.
    brake = std::isfinite(brake) ? std::clamp(brake, -available, available) : 0.0;
    torque[i] = gravity_[i] - brake;
  }
}

}  // namespace comply::pipeline
