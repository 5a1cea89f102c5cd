// Stage "guard": what a running arm must never do, whatever the law and its gains ask (a
// stiffness within the limits can still be more than an arm can render at its effort limits).
// Each condition ends in FAULT, whose hold (gravity + joint damping) stops the motion, with the
// joint and the number named:
//   a joint faster than velocity_factor x its URDF limit for velocity_time_s,
//   a joint more than position_margin_rad past a URDF position limit (the soft limits failed),
//   a joint at its effort limit for saturation_time_s (the law asks for more than the arm has),
//   an oscillation whose energy grows while the command holds still (energy_watch.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

bool Controller::guardMotion() noexcept {
  const StabilityGuardConfig& guard = parameters_.stability_guard;
  if (!guard.enabled) {
    return true;
  }
  char detail[192];
  for (int i = 0; i < dof_; ++i) {
    const char* joint = resolved_->config.joints[static_cast<std::size_t>(i)].c_str();
    const double speed = std::abs(state_.velocity[i]);
    const double allowed = guard.velocity_factor * parameters_.velocity_limit[i];
    overspeed_s_[i] = allowed > 0.0 && speed > allowed ? overspeed_s_[i] + period_s_ : 0.0;
    if (overspeed_s_[i] > guard.velocity_time_s) {
      std::snprintf(detail, sizeof(detail),
                    "%s at %.3g rad/s, over %.3g rad/s (%g x its URDF limit)", joint, speed,
                    allowed, guard.velocity_factor);
      enterFault("stability guard: ", detail);
      return false;
    }
    const double lower = parameters_.soft_limits.lower[i] - guard.position_margin_rad;
    const double upper = parameters_.soft_limits.upper[i] + guard.position_margin_rad;
    const double q = state_.position[i];
    if (q < lower || q > upper) {
      std::snprintf(detail, sizeof(detail),
                    "%s at %.4g, past its URDF limit [%.4g, %.4g] by more than %g", joint, q,
                    parameters_.soft_limits.lower[i], parameters_.soft_limits.upper[i],
                    guard.position_margin_rad);
      enterFault("stability guard: ", detail);
      return false;
    }
  }
  return guardEnergy();
}

namespace {

/// What the sender commands, as the energy rule compares it from cycle to cycle: the reference and
/// its rates, the feedforward, the stiffness. Returns how many values it wrote.
int commandInput(const CommandBus& bus, int dof, std::span<double, EnergyWatch::kMaxInput> out) {
  int n = 0;
  const auto put = [&](const double* values, int count) {
    const int room = std::min(count, static_cast<int>(out.size()) - n);
    std::copy_n(values, room, out.begin() + n);
    n += room;
  };
  if (const auto* cartesian = std::get_if<comply_cartesian_command>(&bus)) {
    put(cartesian->position, 3);
    put(cartesian->orientation, 4);
    put(cartesian->twist, 6);
    put(cartesian->wrench_feedforward, 6);
    put(cartesian->stiffness_translational, 9);
    put(cartesian->stiffness_rotational, 9);
    put(cartesian->torque_feedforward, dof);
    put(cartesian->nullspace_position, dof);
  } else if (const auto* joint = std::get_if<comply_joint_command>(&bus)) {
    put(joint->position, dof);
    put(joint->velocity, dof);
    put(joint->torque_feedforward, dof);
    put(joint->stiffness, dof);
  }
  return n;
}

}  // namespace

bool Controller::guardEnergy() noexcept {
  if (!energy_watch_.enabled() ||
      diagnostics_.state.load(std::memory_order_relaxed) != WrapperState::kActive) {
    return true;
  }
  std::array<double, EnergyWatch::kMaxInput> input{};
  const int size = commandInput(lawBus(), dof_, input);
  if (!energy_watch_.update({state_.velocity.data(), static_cast<std::size_t>(dof_)},
                            {input.data(), static_cast<std::size_t>(size)}, period_s_)) {
    return true;
  }
  const EnergyWatch::Run& run = energy_watch_.run();
  char detail[224];
  std::snprintf(detail, sizeof(detail),
                "an oscillation of %s gained energy from %.3g J to %.3g J in %.2g s, window over "
                "window, while the command held still (energy_growth %g)",
                resolved_->config.joints[static_cast<std::size_t>(run.joint)].c_str(), run.from_j,
                run.to_j, run.duration_s, parameters_.stability_guard.energy_growth);
  enterFault("stability guard: ", detail);
  return false;
}

bool Controller::guardSaturation() noexcept {
  const StabilityGuardConfig& guard = parameters_.stability_guard;
  if (!guard.enabled || guard.saturation_time_s <= 0.0) {
    return true;
  }
  for (int i = 0; i < dof_; ++i) {
    const double limit = parameters_.effort_limit[i];
    saturated_s_[i] = std::abs(torque_[i]) >= limit ? saturated_s_[i] + period_s_ : 0.0;
    if (saturated_s_[i] > guard.saturation_time_s) {
      char detail[192];
      std::snprintf(detail, sizeof(detail), "%s at its effort limit of %.3g N m for %.3g s",
                    resolved_->config.joints[static_cast<std::size_t>(i)].c_str(), limit,
                    saturated_s_[i]);
      enterFault("stability guard: ", detail);
      return false;
    }
  }
  return true;
}

}  // namespace comply::pipeline
