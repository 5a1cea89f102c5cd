// Stage "guard": what a running arm must never do, whatever the law and its gains ask (a
// stiffness within the limits can still be more than an arm can render at its effort limits).
// Each condition ends in FAULT, whose hold (gravity + joint damping) stops the motion, with the
// joint and the number named:
//   a joint faster than velocity_factor x its URDF limit for velocity_time_s,
//   a joint more than position_margin_rad past a URDF position limit (the soft limits failed),
//   a joint at its effort limit for saturation_time_s (the law asks for more than the arm has),
//   an oscillation whose energy grows while the command holds still (energy_watch.hpp).

#include <cmath>
#include <cstdio>
#include <cstring>
#include <variant>

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

/// Whether two buses hold the same command, byte for byte (padding included: a difference there
/// only makes the energy rule wait a window).
bool sameBus(const CommandBus& a, const CommandBus& b) noexcept {
  if (a.index() != b.index()) {
    return false;
  }
  return std::visit(
      [&](const auto& bus) {
        using Bus = std::decay_t<decltype(bus)>;
        return std::memcmp(&bus, &std::get<Bus>(b), sizeof(Bus)) == 0;
      },
      a);
}

}  // namespace

bool Controller::guardEnergy() noexcept {
  if (!energy_watch_.enabled() ||
      diagnostics_.state.load(std::memory_order_relaxed) != WrapperState::kActive) {
    return true;
  }
  const CommandBus& bus = lawBus();
  const bool changed = !sameBus(bus, energy_bus_);
  if (changed) {
    energy_bus_ = bus;
  }
  if (!energy_watch_.update({state_.velocity.data(), static_cast<std::size_t>(dof_)}, changed,
                            period_s_)) {
    return true;
  }
  const EnergyWatch::Run& run = energy_watch_.run();
  char detail[224];
  std::snprintf(detail, sizeof(detail),
                "an oscillation of %s gained energy from %.3g J to %.3g J in %.3g s, window over "
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
