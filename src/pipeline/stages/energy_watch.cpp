// The stability guard's energy rule (see energy_watch.hpp).

#include "comply/pipeline/energy_watch.hpp"

#include <algorithm>
#include <cmath>

namespace comply::pipeline {

void EnergyWatch::configure(const Options& options, std::span<const double> inertia) noexcept {
  options_ = options;
  dof_ = static_cast<int>(std::min<std::size_t>(inertia.size(), kMaxDof));
  inertia_.setOnes(dof_);
  for (int i = 0; i < dof_; ++i) {
    if (inertia[static_cast<std::size_t>(i)] > 0.0) {
      inertia_[i] = inertia[static_cast<std::size_t>(i)];
    }
  }
  reset();
}

void EnergyWatch::reset() noexcept {
  startWindow();
  last_sign_.setZero(dof_);
  swing_speed_.setZero(dof_);
  have_previous_ = false;
  previous_kinetic_j_ = 0.0;
  run_from_j_ = 0.0;
  run_to_j_ = 0.0;
  run_windows_ = 0;
  run_joint_ = 0;
  tripped_ = {};
}

bool EnergyWatch::update(std::span<const double> velocity, bool command_changed,
                         double period_s) noexcept {
  if (!enabled() || dof_ == 0) {
    return false;
  }
  double kinetic_j = 0.0;
  const int joints = std::min(dof_, static_cast<int>(velocity.size()));
  for (int i = 0; i < joints; ++i) {
    const double dq = velocity[static_cast<std::size_t>(i)];
    const double share_j = 0.5 * inertia_[i] * dq * dq;
    kinetic_j += share_j;
    joint_peak_j_[i] = std::max(joint_peak_j_[i], share_j);
    speed_peak_[i] = std::max(speed_peak_[i], std::abs(dq));
    // A reversal counts once the speed is a tenth of the joint's last peak: noise around rest
    // does not swing.
    if (swing_speed_[i] > 0.0 && std::abs(dq) > 0.1 * swing_speed_[i]) {
      const double sign = dq > 0.0 ? 1.0 : -1.0;
      if (last_sign_[i] != 0.0 && sign != last_sign_[i]) {
        reversals_[i] += 1.0;
      }
      last_sign_[i] = sign;
    }
  }
  kinetic_peak_j_ = std::max(kinetic_peak_j_, kinetic_j);

  input_changed_ = input_changed_ || command_changed;

  elapsed_s_ += period_s;
  if (elapsed_s_ < options_.window_s) {
    return false;
  }
  closeWindow();
  return tripped();
}

void EnergyWatch::closeWindow() noexcept {
  int dominant = 0;
  for (int i = 1; i < dof_; ++i) {
    if (joint_peak_j_[i] > joint_peak_j_[dominant]) {
      dominant = i;
    }
  }
  const bool rose = have_previous_ && kinetic_peak_j_ >= kStepGrowth * previous_kinetic_j_ &&
                    kinetic_peak_j_ > 0.0;
  const bool swung = reversals_[dominant] >= 2.0;
  if (rose && !input_changed_ && swung) {
    if (run_windows_ == 0) {
      run_from_j_ = previous_kinetic_j_;
      run_joint_ = dominant;
    }
    ++run_windows_;
    run_to_j_ = kinetic_peak_j_;
  } else {
    run_windows_ = 0;
  }
  have_previous_ = true;
  previous_kinetic_j_ = kinetic_peak_j_;
  swing_speed_ = speed_peak_;
  if (tripped()) {
    tripped_ = {run_from_j_, run_to_j_, run_windows_ * elapsed_s_, run_joint_};
  }
  startWindow();
}

void EnergyWatch::startWindow() noexcept {
  elapsed_s_ = 0.0;
  kinetic_peak_j_ = 0.0;
  input_changed_ = false;
  joint_peak_j_.setZero(dof_);
  reversals_.setZero(dof_);
  speed_peak_.setZero(dof_);
}

bool EnergyWatch::tripped() const noexcept {
  return run_windows_ >= kMinRunWindows && run_to_j_ > options_.floor_j &&
         run_to_j_ >= options_.growth * std::max(run_from_j_, 1e-12);
}

}  // namespace comply::pipeline
