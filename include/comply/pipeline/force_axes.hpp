#pragma once
// Stage "force": force along axes of the task frame (hybrid force/impedance control), between the
// gain stage and the law, for every Cartesian law, without the law knowing.
//
// A command selects task axes (force_axes, 1 = force) and the wrench the TCP is to exert on the
// environment along them (wrench_target, task frame). Along a selected axis the stage turns the
// command the law reads into a force source:
//   - the spring is taken out: the reference is moved onto the measured pose along the axis, so
//     the pose error there is zero whatever the command's position (the stiffness stays, so that
//     damping ratios keep the damping of the commanded impedance);
//   - the commanded velocity and acceleration along the axis are zeroed: the law's damping acts on
//     the measured velocity there;
//   - the force loop's output is added to wrench_feedforward:
//       F = F_d + k_p (F_d - F) + k_i integral(F_d - F) dt,
//     F the exerted wrench estimated this cycle (force_control.source). The integral term is kept
//     within +-integral_limit (anti-windup) and frozen while the speed bound acts;
//   - the speed bound: with the TCP moving along the axis, in the direction it pushes, faster than
//     max_speed, the push fades linearly to nothing at twice max_speed (free space, a lost
//     contact). The law's damping then brakes.
// The other axes stay impedance. Everything is recomputed in the task frame of the command every
// cycle, so a task frame that turns with a surface carries its force axis along.
//
// Contact-force limit (contact_force_limit_n, contact_torque_limit_n_m; a safety option on every
// axis): on an impedance axis whose exerted force is above its limit, in the direction the spring
// pushes, the reference is pulled back toward the measured pose at the rate
//   d pull / dt = 2 pi limit_bandwidth_hz (|F| - limit) / K_axis   (at most max_speed),
// which settles the force at the limit against any surface stiffer than the spring, and returns
// the reference as the force falls below it; the feedforward along the axis is clipped to the
// limit. On a force axis the feedforward along it (the command's and the force loop's) is
// clipped to the limit. A cycle without a wrench estimate holds the pull-back where it is. The
// damping of a commanded velocity into the contact is not limited.
//
// The law then reads force_axes all zero: the stage has already done what they ask. Real-time: no
// allocation, no lock, no exception.

#include "comply/core/commands.hpp"
#include "comply/core/enum_names.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/option_table.hpp"
#include "comply/plugin/abi.h"

namespace comply::pipeline {

/// Moves `bus`'s reference along the force axes it selects (its task frame, translational and
/// rotational) onto the measured pose `position`, `orientation`, as the stage does every cycle;
/// along the other axes the pose error is unchanged. Called wherever force axes may end, so an
/// axis leaving force control holds the arm where it is. Real-time.
void anchorForceAxes(comply_cartesian_command& bus, const Eigen::Vector3d& position,
                     const Eigen::Quaterniond& orientation) noexcept;

/// Which wrench estimate the force loop reads.
enum class ForceSource : std::uint8_t {
  kAuto,      ///< the state's: the momentum observer when it runs, else the wrist sensor
  kObserver,  ///< the momentum observer (observer.enabled)
  kSensor,    ///< the wrist force/torque sensor
};
inline constexpr EnumNames<ForceSource, 3> kForceSourceNames{{{ForceSource::kAuto, "auto"},
                                                              {ForceSource::kObserver, "observer"},
                                                              {ForceSource::kSensor, "sensor"}}};

/// force_control.* in the controller file.
struct ForceControlConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_FORCE_CONTROL_OPTIONS)
};

class ForceAxes {
 public:
  void configure(const ForceControlConfig& config) noexcept;
  /// On activation: no integral, no pull-back.
  void reset() noexcept;
  /// Whether a contact-force limit is configured (the stage then runs on every command).
  [[nodiscard]] bool limited() const noexcept { return limited_; }

  /// Whether the stage acts on `in`: it selects a force axis, or a limit is configured. When not,
  /// the law reads `in` itself (and the caller resets the stage).
  [[nodiscard]] bool acts(const comply_cartesian_command& in) const noexcept;

  /// One cycle on a command the stage acts on. `in`: the command the law would read; `data`: this
  /// cycle's pose; `tcp_twist`: J dq, base frame; `wrench_on_tool`: the estimate of what the
  /// environment exerts on the tool at the TCP (base frame, force first), or nullptr when there is
  /// none this cycle (the loop then pushes F_d plus the integral term it holds, and a pull-back
  /// holds). Writes the law's command to `out`.
  void apply(const comply_cartesian_command& in, const model::Data& data, const Vector6d& tcp_twist,
             const Vector6d* wrench_on_tool, double period_s,
             comply_cartesian_command& out) noexcept;

  /// Last cycle, task frame, force first: the force loop's output on the force axes (zero on the
  /// others) [N, N m].
  [[nodiscard]] const Vector6d& forceCommand() const noexcept { return force_command_; }
  /// Last cycle, task frame: how far each impedance axis's reference is pulled back [m, rad].
  [[nodiscard]] const Vector6d& pullBack() const noexcept { return pull_back_; }

 private:
  /// One force axis: the loop's push along it.
  double forceLoop(int axis, double target, double exerted, bool estimated, double speed,
                   double period_s) noexcept;
  /// One impedance axis under a limit: the pose error it keeps after the pull-back.
  double limitAxis(int axis, double error, double exerted, bool estimated, double stiffness,
                   double period_s) noexcept;

  ForceControlConfig config_;
  Vector6d limit_ = Vector6d::Zero();           // per task axis; 0: none
  Vector6d integral_limit_ = Vector6d::Zero();  // per task axis
  Vector6d max_speed_ = Vector6d::Zero();       // per task axis
  bool limited_ = false;
  Vector6d integral_ = Vector6d::Zero();  // integral of the force error [N s]
  Vector6d pull_back_ = Vector6d::Zero();
  Vector6d force_command_ = Vector6d::Zero();
};

}  // namespace comply::pipeline
