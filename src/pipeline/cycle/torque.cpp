// Stages "compensate", "shape" and "write", and the safe state "hold": what is added to the law's
// torque, how the sum is shaped for the motors, and what goes out in FAULT (safe_hold.hpp).

#include <algorithm>
#include <cmath>

#include "comply/pipeline/compensation.hpp"
#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::compensate() noexcept {
  if (parameters_.gravity_compensation && !parameters_.hardware_compensates_gravity) {
    torque_ += data_.gravity.head(dof_);
  }
  if (parameters_.payload_compensation) {
    torque_ += data_.payload_gravity.head(dof_);
  }
  if (parameters_.friction.model != FrictionModel::kNone) {
    frictionTorque(parameters_.friction, state_.velocity, scratch_);
    torque_ += scratch_;
  }
  if (parameters_.soft_limits.enabled) {
    softLimitTorque(parameters_.soft_limits, state_.position, state_.velocity, scratch_);
    torque_ += scratch_;
  }
}

void Controller::govern() noexcept {
  governed_ = governor_.apply(state_, tcp_twist_, data_, period_s_, law_torque_, torque_).acted();
  if (governed_) {
    diagnostics_.governor_hits.fetch_add(1, std::memory_order_relaxed);
  }
}

void Controller::scaleIntoLimits() noexcept {
  // The largest share s of the law's torque that keeps every joint within its limit with the
  // compensation added in full: a wrench the arm cannot give whole is given in its direction.
  double share = 1.0;
  int binding = -1;
  for (int i = 0; i < dof_; ++i) {
    const double law = law_torque_[i];
    const double compensation = torque_[i] - law;
    const double limit = parameters_.effort_limit[i];
    if (std::abs(torque_[i]) <= limit || law == 0.0) {
      continue;
    }
    const double joint_share = ((law > 0.0 ? limit : -limit) - compensation) / law;
    if (joint_share < share) {
      share = std::max(joint_share, 0.0);
      binding = i;
    }
  }
  if (binding < 0) {
    return;
  }
  for (int i = 0; i < dof_; ++i) {
    torque_[i] -= (1.0 - share) * law_torque_[i];
  }
  diagnostics_.effort_limit_hits.fetch_add(1, std::memory_order_relaxed);
}

bool Controller::shape() noexcept {
  if (parameters_.effort_saturation == EffortSaturation::kScale) {
    scaleIntoLimits();
  }
  const ShapingResult shaped = shaper_.apply(torque_, period_s_);
  if (!shaped.finite) {
    enterFault("shaping: ", "non-finite torque after compensation and filtering");
    return false;
  }
  diagnostics_.rate_limit_hits.fetch_add(shaped.rate_limited, std::memory_order_relaxed);
  diagnostics_.effort_limit_hits.fetch_add(shaped.effort_limited, std::memory_order_relaxed);
  // The energy tank learns from the torque that acted: not the law's when clipped or governed.
  torque_clipped_ =
      shaped.rate_limited + shaped.effort_limited > 0 || governed_ || slowed_ || walled_;
  return true;
}

CycleStatus Controller::write(std::span<double> torque) noexcept {
  for (int i = 0; i < dof_; ++i) {
    torque[i] = torque_[i];
  }
  return CycleStatus::kOk;
}

CycleStatus Controller::hold(std::span<double> torque) noexcept {
  force_active_ = false;  // no law runs: what it would read is the command in force
  walls_active_ = false;
  walled_ = false;
  slowed_ = false;
  contact_speed_.hold();  // nothing scaled, nothing braked
  if (walls_.enabled()) {
    // The barrier does not act in a hold; the distance is this cycle's (the last usable pose's
    // when this cycle's state is not).
    walls_.observe(data_.tip_position);
  }
  // The state is the last usable one when this cycle's was not.
  // A stale velocity (a frozen stream, or this cycle's state unusable: state_ is the last usable
  // one) would brake against a motion the arm may no longer have.
  safe_hold_.torque(state_, frozen_.frozen() || !state_usable_, period_s_, torque_);
  const ShapingResult shaped = shaper_.apply(torque_, period_s_, /*filter=*/false);
  if (!shaped.finite) {
    // Nothing finite to hold with (no usable state was ever measured): command no torque rather
    // than repeat the last output, which may be the faulty law's.
    torque_.setZero();
    shaper_.reset(torque_);
  }
  diagnostics_.rate_limit_hits.fetch_add(shaped.rate_limited, std::memory_order_relaxed);
  diagnostics_.effort_limit_hits.fetch_add(shaped.effort_limited, std::memory_order_relaxed);
  for (int i = 0; i < dof_ && i < static_cast<int>(torque.size()); ++i) {
    torque[i] = torque_[i];
  }
  return CycleStatus::kFault;
}

}  // namespace comply::pipeline
