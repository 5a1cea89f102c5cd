#pragma once
// Stage "reflex": a contact the task did not plan for, caught from the contact wrench (the state's
// contact_wrench: the momentum observer's estimate when observer.enabled, else the wrist sensor's
// reading) and answered as the controller file says (reflex.*). After the commands and the sensor
// check, before anything renders the command in force; every law, joint and Cartesian.
//
// Thresholds. Per task axis, in the task frame of the command in force (the base frame under
// joint control): force T_f = (T_x, T_y, T_z) [N] and torque T_t [N m]. They are the semi-axes
// of an ellipsoid: the force trips when sum_i (F_i / T_i)^2 > 1, the torque likewise. With equal
// entries that is |F| > T, the same in every direction (a box of per-axis limits would let a push
// between two axes through at up to sqrt(3) T); raising one entry lets the task press along that
// axis alone while a push across it still trips at the others. The file sets one value for every
// axis (reflex.force_n, reflex.torque_nm); a command's reflex_force and reflex_torque set them per
// axis for its phase, within the file's ceilings (reflex.max_force_n, max_torque_nm; the intake
// refuses more), a 0 entry meaning the file's value. A reset request returns them to the file's.
//
// Debounce. The wrench must stay above for reflex.debounce_s (the first sample above starts the
// count; a sample below ends it) before the reflex trips: one noisy sample does not. A cycle
// without an estimate neither counts nor ends the count; 0.1 s without one is a FAULT, since the
// reflex the file asks for cannot act (no observer, no wrist reading).
//
// Reactions (reflex.reaction), in the cycle that trips:
//   hold     the reference becomes the measured pose, at rest, without feedforward or force axes;
//            the stiffness in force scaled by hold_stiffness_fraction;
//   retreat  the same, and the reference then moves from the pose at the trip along the contact
//            force (the environment's push: away from what it touches) by retreat_m at
//            retreat_speed_m_per_s, then holds. A trip on the torque alone holds: a torque gives
//            no direction to back off along. Cartesian laws only;
//   fault    FAULT, naming the wrench and the thresholds.
// Hold and retreat latch: until an operator's reset request, commands and chunks are refused
// (reflex_latched; one the intake accepted before it saw the trip is taken without effect), and
// the reset resumes from the measured pose, never from the command that was in force.
//
// Real-time: no allocation, no lock, no exception.

#include <cstdint>

#include "comply/core/commands.hpp"
#include "comply/core/enum_names.hpp"
#include "comply/pipeline/option_table.hpp"

namespace comply::pipeline {

/// What the cycle does when the reflex trips (reflex.reaction).
enum class ReflexReaction : std::uint8_t {
  kHold,     ///< the measured pose held, motion stopped
  kRetreat,  ///< back off along the contact force by retreat_m, then hold
  kFault,    ///< FAULT
};
inline constexpr EnumNames<ReflexReaction, 3> kReflexReactionNames{
    {{ReflexReaction::kHold, "hold"},
     {ReflexReaction::kRetreat, "retreat"},
     {ReflexReaction::kFault, "fault"}}};

/// reflex.* in the controller file.
struct ReflexConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_REFLEX_OPTIONS)
};

/// The thresholds in force, per task axis (x y z).
struct ReflexThresholds {
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_nm = Eigen::Vector3d::Zero();
};

class ContactReflex {
 public:
  /// What one cycle's check found.
  enum class Check : std::uint8_t {
    kArmed,       ///< within the thresholds, or above them for less than the debounce
    kTripped,     ///< above them for the debounce: react now
    kNoEstimate,  ///< no contact wrench for kNoEstimateTimeoutS: the reflex cannot act
  };
  /// How long the cycle may go without a contact wrench while the reflex is on [s].
  static constexpr double kNoEstimateTimeoutS = 0.1;

  explicit ContactReflex(const ReflexConfig& config) noexcept : config_(config) { reset(); }

  [[nodiscard]] bool enabled() const noexcept { return config_.enabled; }
  [[nodiscard]] const ReflexConfig& config() const noexcept { return config_; }
  /// Armed again, nothing counted: activation, a reset request.
  void reset() noexcept;

  /// The thresholds a command in force asks for: each entry of `force` [N] and `torque` [N m]
  /// above 0 as it is, a 0 entry the file's value.
  [[nodiscard]] ReflexThresholds thresholds(const double* force,
                                            const double* torque) const noexcept;

  /// One cycle while armed. `wrench`: the contact wrench on the tool at the TCP, base frame, force
  /// first [N, N m] (nullptr: none this cycle); `task`: the task frame's orientation in the base
  /// frame, a unit quaternion. On kTripped the trip is recorded (tripped(), wrench(), detail()); on
  /// kNoEstimate, detail() says why.
  Check check(const Vector6d* wrench, const Eigen::Quaterniond& task,
              const ReflexThresholds& thresholds, double period_s) noexcept;

  /// Tripped since the last reset().
  [[nodiscard]] bool tripped() const noexcept { return tripped_; }
  /// Tripped and holding (hold, retreat): commands wait for a reset.
  [[nodiscard]] bool latched() const noexcept {
    return tripped_ && config_.reaction != ReflexReaction::kFault;
  }
  /// The thresholds of the last check (the state reports them).
  [[nodiscard]] const ReflexThresholds& inForce() const noexcept { return in_force_; }
  /// The wrench that tripped it, task frame then, force first; zero while armed.
  [[nodiscard]] const Vector6d& wrench() const noexcept { return tripped_wrench_task_; }
  /// Why it tripped, or why it cannot act (kNoEstimate).
  [[nodiscard]] const char* detail() const noexcept { return detail_; }

  /// The retreat: the TCP's position at the trip is `start`; the reference's position and
  /// velocity [m, m/s] `elapsed_s` after the trip. At rest on `start` when the trip gave no
  /// direction (torque alone) or retreat_m is 0.
  void startRetreat(const Eigen::Vector3d& start) noexcept;
  void retreat(double elapsed_s, Eigen::Vector3d& position,
               Eigen::Vector3d& velocity) const noexcept;

 private:
  void describeTrip(const Vector6d& task_wrench, const ReflexThresholds& thresholds,
                    double force_ratio, double torque_ratio) noexcept;

  ReflexConfig config_;
  ReflexThresholds in_force_;
  double above_s_ = -1.0;   // how long above the thresholds; < 0: below
  double without_s_ = 0.0;  // how long without an estimate
  bool tripped_ = false;
  Vector6d tripped_wrench_task_ = Vector6d::Zero();
  Eigen::Vector3d retreat_direction_ = Eigen::Vector3d::Zero();  // base frame, unit or zero
  Eigen::Vector3d retreat_start_ = Eigen::Vector3d::Zero();
  char detail_[320] = {};
};

}  // namespace comply::pipeline
