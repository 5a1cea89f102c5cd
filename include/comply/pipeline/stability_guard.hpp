#pragma once
// Stage "guard": what a running arm must never do, whatever the law and its gains ask (a stiffness
// within the limits can still be more than an arm can render at its effort limits). Each rule
// names the joint and the number; the controller turns a broken rule into a FAULT:
//   motion      a joint faster than velocity_factor x its URDF limit for velocity_time_s, or
//               more than position_margin_rad past a URDF position limit (the soft limits failed);
//   energy      an oscillation whose energy grows while the command holds still (energy_watch.hpp);
//   saturation  a joint at its effort limit for saturation_time_s (the law asks for more than the
//               arm has): checked on the shaped torque, after the law.
//
// Real-time: the checks allocate nothing, take no lock, never throw.

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/energy_watch.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class StabilityGuard {
 public:
  explicit StabilityGuard(const ResolvedController& resolved);

  /// Forgets how long each rule has held (activation).
  void reset() noexcept;
  /// The motion rules at the measured `state`; false when one broke (detail() says which).
  bool checkMotion(const JointState& state, double period_s) noexcept;
  /// The energy rule: `law_bus` is the command the law acted on in the last cycle.
  bool checkEnergy(const JointState& state, const CommandBus& law_bus, double period_s) noexcept;
  /// The saturation rule on the torque the cycle is about to write.
  bool checkSaturation(const JointVector& torque, double period_s) noexcept;
  /// What the last broken rule found, naming the joint.
  [[nodiscard]] const char* detail() const noexcept { return detail_; }

 private:
  const ResolvedController& resolved_;
  const CycleParameters& parameters_;
  // From the configuration, once: the speed no joint may keep [rad/s | m/s], and the positions
  // past which a joint has left its URDF range by more than the margin [rad | m].
  JointVector allowed_speed_;
  JointVector lowest_;
  JointVector highest_;
  JointVector overspeed_s_;   // per joint: how long it has been over its speed limit
  JointVector saturated_s_;   // per joint: how long it has sat at its effort limit
  EnergyWatch energy_watch_;  // the energy rule
  CommandBus energy_bus_;     // the law's command the energy rule saw last
  char detail_[224] = {};
};

}  // namespace comply::pipeline
