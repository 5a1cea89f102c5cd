#include "comply/pipeline/stability_guard.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <variant>

namespace comply::pipeline {
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
        return std::memcmp(&bus, std::get_if<Bus>(&b), sizeof(Bus)) == 0;
      },
      a);
}

}  // namespace

StabilityGuard::StabilityGuard(const ResolvedController& resolved)
    : resolved_(resolved), parameters_(resolved.parameters) {
  overspeed_s_.setZero(resolved.dof);
  saturated_s_.setZero(resolved.dof);
  const StabilityGuardConfig& guard = parameters_.stability_guard;
  allowed_speed_ = guard.velocity_factor * parameters_.velocity_limit;
  lowest_ = parameters_.soft_limits.lower.array() - guard.position_margin_rad;
  highest_ = parameters_.soft_limits.upper.array() + guard.position_margin_rad;
  energy_watch_.configure({.window_s = guard.enabled ? guard.energy_window_s : 0.0,
                           .growth = guard.energy_growth,
                           .floor_j = guard.energy_floor_j},
                          {parameters_.joint_inertia.data(),
                           static_cast<std::size_t>(parameters_.joint_inertia.size())});
}

void StabilityGuard::reset() noexcept {
  overspeed_s_.setZero();
  saturated_s_.setZero();
  energy_watch_.reset();
}

bool StabilityGuard::checkMotion(const JointState& state, double period_s) noexcept {
  const StabilityGuardConfig& guard = parameters_.stability_guard;
  if (!guard.enabled) {
    return true;
  }
  for (int i = 0; i < resolved_.dof; ++i) {
    const char* joint = resolved_.config.joints[static_cast<std::size_t>(i)].c_str();
    const double speed = std::abs(state.velocity[i]);
    const double allowed = allowed_speed_[i];
    overspeed_s_[i] = allowed > 0.0 && speed > allowed ? overspeed_s_[i] + period_s : 0.0;
    if (overspeed_s_[i] > guard.velocity_time_s) {
      std::snprintf(detail_, sizeof(detail_),
                    "%s at %.3g rad/s, over %.3g rad/s (%g x its URDF limit)", joint, speed,
                    allowed, guard.velocity_factor);
      return false;
    }
    const double q = state.position[i];
    if (q < lowest_[i] || q > highest_[i]) {
      std::snprintf(detail_, sizeof(detail_),
                    "%s at %.4g, past its URDF limit [%.4g, %.4g] by more than %g", joint, q,
                    parameters_.soft_limits.lower[i], parameters_.soft_limits.upper[i],
                    guard.position_margin_rad);
      return false;
    }
  }
  return true;
}

bool StabilityGuard::checkEnergy(const JointState& state, const CommandBus& law_bus,
                                 double period_s) noexcept {
  if (!energy_watch_.enabled()) {
    return true;
  }
  const bool changed = !sameBus(law_bus, energy_bus_);
  if (changed) {
    energy_bus_ = law_bus;
  }
  if (!energy_watch_.update({state.velocity.data(), static_cast<std::size_t>(resolved_.dof)},
                            changed, period_s)) {
    return true;
  }
  const EnergyWatch::Run& run = energy_watch_.run();
  std::snprintf(detail_, sizeof(detail_),
                "an oscillation of %s gained energy from %.3g J to %.3g J in %.3g s, window over "
                "window, while the command held still (energy_growth %g)",
                resolved_.config.joints[static_cast<std::size_t>(run.joint)].c_str(), run.from_j,
                run.to_j, run.duration_s, parameters_.stability_guard.energy_growth);
  return false;
}

bool StabilityGuard::checkSaturation(const JointVector& torque, double period_s) noexcept {
  const StabilityGuardConfig& guard = parameters_.stability_guard;
  if (!guard.enabled || guard.saturation_time_s <= 0.0) {
    return true;
  }
  for (int i = 0; i < resolved_.dof; ++i) {
    const double limit = parameters_.effort_limit[i];
    saturated_s_[i] = std::abs(torque[i]) >= limit ? saturated_s_[i] + period_s : 0.0;
    if (saturated_s_[i] > guard.saturation_time_s) {
      std::snprintf(detail_, sizeof(detail_), "%s at its effort limit of %.3g N m for %.3g s",
                    resolved_.config.joints[static_cast<std::size_t>(i)].c_str(), limit,
                    saturated_s_[i]);
      return false;
    }
  }
  return true;
}

}  // namespace comply::pipeline
