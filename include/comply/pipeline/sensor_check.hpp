#pragma once
// Stage "sensor check": whether the wrist sensor's wrench (wrist_sensor.hpp: the declared tool's
// weight and the tare off) can be trusted, before it moves the arm and while it does.
//
//   at rest   Where the reading acts on the arm without a sender asking for it (admittance; a
//             declared tool, compensation.payload; a contact-force limit the force stage reads
//             from the sensor), the first reading after activation with every joint slower than
//             kRestSpeedRadPerS is compared with zero. At rest and out of contact what is left is
//             the sensor's bias plus the declared tool's error: a tool declared but not mounted
//             reads as a push of its weight upward, and moves an admittance arm. Above
//             wrench_sensor.rest_force_tolerance_n or rest_torque_tolerance_n_m (each plus
//             rest_payload_fraction of the declared tool's weight, or of its moment about the TCP)
//             it is a FAULT before the arm moves, naming the declared mass and the one the sensor
//             measures along gravity. A check that failed stays armed: the reset after it checks
//             again (a tare in between takes the reading as the zero).
//   observer  With the momentum observer running and wrench_sensor.observer_tolerance_n > 0, the
//             sensor's force is compared with the observer's every cycle, the sensor's passed
//             through the observer's own first-order filter (gain_per_s) so that both lag alike:
//             a disagreement above the tolerance for kDisagreementS is a FAULT (a sensor whose
//             bias drifted since activation, which the rest check cannot see).
//
// Real-time: no allocation, no lock, no exception.

#include "comply/core/capacity.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class SensorCheck {
 public:
  /// Below this every joint is "at rest" for the rest check [rad/s | m/s].
  static constexpr double kRestSpeedRadPerS = 0.05;
  /// How long the sensor and the observer may disagree before a FAULT [s].
  static constexpr double kDisagreementS = 0.1;

  explicit SensorCheck(const ResolvedController& resolved) noexcept;

  /// Activation: the next reading at rest is checked; the comparison with the observer starts
  /// afresh (both from zero, as the observer does).
  void reset() noexcept;
  /// After a reset of a FAULT: the comparison starts afresh; the rest check stays as it was (armed
  /// only if it has not passed since activation).
  void restart() noexcept;

  /// Whether the rest check applies to this controller at all.
  [[nodiscard]] bool checksAtRest() const noexcept { return at_rest_; }
  /// Whether the rest check still waits for a reading at rest.
  [[nodiscard]] bool armed() const noexcept { return armed_; }
  /// Whether the sensor is compared with the observer (both configured).
  [[nodiscard]] bool comparesWithObserver() const noexcept { return observer_gain_per_s_ > 0.0; }

  /// The rest check on this cycle's reading `wrench` (base frame, at the TCP, force first: the
  /// tool and the tare off) at joint speeds `velocity`. False on a mismatch (detail()); true
  /// otherwise, and disarmed once a reading at rest has passed.
  bool checkAtRest(const Vector6d& wrench, const JointVector& velocity) noexcept;
  /// This cycle's sensor and observer wrenches (base frame, at the TCP): false once their forces
  /// have disagreed by more than the tolerance for kDisagreementS (detail()).
  bool compareWithObserver(const Vector6d& sensor, const Vector6d& observer,
                           double period_s) noexcept;

  [[nodiscard]] const char* detail() const noexcept { return detail_; }

 private:
  void describeMismatch(const Vector6d& wrench, double force_tolerance_n,
                        double torque_tolerance_n_m) noexcept;

  bool at_rest_ = false;  // the rest check applies
  bool armed_ = false;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();        // [m/s^2], base frame
  Eigen::Vector3d tool_weight_n_ = Eigen::Vector3d::Zero();  // declared, on the sensor
  double tool_mass_kg_ = 0.0;
  double tool_moment_n_m_ = 0.0;  // |weight| x |centre of mass|: its largest moment at the TCP
  double force_tolerance_n_ = 0.0;
  double torque_tolerance_n_m_ = 0.0;
  double observer_gain_per_s_ = 0.0;  // 0: not compared
  double observer_tolerance_n_ = 0.0;
  Eigen::Vector3d sensor_filtered_n_ = Eigen::Vector3d::Zero();
  bool from_observer_ = false;  // the next comparison seeds the filter from the observer
  double disagreeing_s_ = 0.0;
  char detail_[240] = {};  // with "wrist sensor: ", within a diagnostics message (256)
};

}  // namespace comply::pipeline
