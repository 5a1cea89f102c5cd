#include "comply/pipeline/sensor_check.hpp"

#include <cmath>
#include <cstdio>

#include "comply/pipeline/force_axes.hpp"

namespace comply::pipeline {
namespace {

/// Whether the force stage reads its wrench from the wrist sensor under a contact-force limit:
/// the limit then trusts the sensor on every command.
bool limitReadsSensor(const ResolvedController& resolved) {
  const CycleParameters& parameters = resolved.parameters;
  const ForceControlConfig& force = parameters.force_control;
  const bool limited = (force.contact_force_limit_n.array() > 0.0).any() ||
                       (force.contact_torque_limit_n_m.array() > 0.0).any();
  const bool from_sensor = force.source == ForceSource::kSensor ||
                           (force.source == ForceSource::kAuto && !parameters.observer.enabled);
  return resolved.cartesian() && limited && from_sensor;
}

}  // namespace

SensorCheck::SensorCheck(const ResolvedController& resolved) noexcept {
  const CycleParameters& parameters = resolved.parameters;
  const WrenchSensorConfig& sensor = parameters.wrench_sensor;
  gravity_ = resolved.model->gravity();
  const bool tool = parameters.payload_on_sensor && parameters.payload.mass_kg > 0.0;
  if (tool) {
    tool_mass_kg_ = parameters.payload.mass_kg;
    tool_weight_n_ = tool_mass_kg_ * gravity_;
    tool_moment_n_m_ = tool_weight_n_.norm() * parameters.payload.com_in_tip.norm();
  }
  at_rest_ = isAdmittance(parameters.output.mode) || tool || limitReadsSensor(resolved);
  force_tolerance_n_ =
      sensor.rest_force_tolerance_n + sensor.rest_payload_fraction * tool_weight_n_.norm();
  torque_tolerance_n_m_ =
      sensor.rest_torque_tolerance_n_m + sensor.rest_payload_fraction * tool_moment_n_m_;
  if (parameters.observer.enabled && sensor.observer_tolerance_n > 0.0) {
    observer_gain_per_s_ = parameters.observer.gain_per_s;
    observer_tolerance_n_ = sensor.observer_tolerance_n;
  }
  reset();
}

void SensorCheck::reset() noexcept {
  armed_ = at_rest_;
  sensor_filtered_n_.setZero();  // the observer starts from zero too (activation)
  from_observer_ = false;
  disagreeing_s_ = 0.0;
}

void SensorCheck::restart() noexcept {
  // After a reset the observer keeps its estimate: the sensor's filter starts from it.
  from_observer_ = true;
  disagreeing_s_ = 0.0;
}

bool SensorCheck::checkAtRest(const Vector6d& wrench, const JointVector& velocity) noexcept {
  if (!armed_ || velocity.cwiseAbs().maxCoeff() >= kRestSpeedRadPerS) {
    return true;  // nothing to check, or the arm moves: the tool's inertial force is in the reading
  }
  if (wrench.head<3>().norm() <= force_tolerance_n_ &&
      wrench.tail<3>().norm() <= torque_tolerance_n_m_) {
    armed_ = false;
    return true;
  }
  describeMismatch(wrench, force_tolerance_n_, torque_tolerance_n_m_);
  return false;  // stays armed: the reset after the FAULT checks again
}

void SensorCheck::describeMismatch(const Vector6d& wrench, double force_tolerance_n,
                                   double torque_tolerance_n_m) noexcept {
  // What the sensor carries along gravity, the tare off: the reading plus the declared weight
  // that came off it, as a mass.
  const double g2 = gravity_.squaredNorm();
  const double measured_kg =
      g2 > 0.0 ? (wrench.head<3>() + tool_weight_n_).dot(gravity_) / g2 : 0.0;
  if (tool_mass_kg_ > 0.0) {
    std::snprintf(detail_, sizeof(detail_),
                  "the declared tool (compensation.payload.mass_kg %.2f kg) does not match the "
                  "reading at rest, %.2f kg along gravity: %.1f N, %.2f N m left (tolerance "
                  "%.2f N, %.2f N m); mount it or fix the file, or tare a bias, then reset",
                  tool_mass_kg_, measured_kg, wrench.head<3>().norm(), wrench.tail<3>().norm(),
                  force_tolerance_n, torque_tolerance_n_m);
  } else {
    std::snprintf(detail_, sizeof(detail_),
                  "the reading at rest is %.1f N, %.2f N m after the tare (tolerance %.2f N, "
                  "%.2f N m; %.2f kg along gravity): a bias, an undeclared tool or a contact; "
                  "tare out of contact, then reset",
                  wrench.head<3>().norm(), wrench.tail<3>().norm(), force_tolerance_n,
                  torque_tolerance_n_m, measured_kg);
  }
}

bool SensorCheck::compareWithObserver(const Vector6d& sensor, const Vector6d& observer,
                                      double period_s) noexcept {
  if (observer_gain_per_s_ <= 0.0) {
    return true;
  }
  // The observer's residual follows the external torque as dr/dt = K_O (tau_ext - r) from zero
  // at activation: the sensor's force through the same filter, from zero, lags alike.
  if (from_observer_) {
    sensor_filtered_n_ = observer.head<3>();
    from_observer_ = false;
  }
  const double alpha = 1.0 - std::exp(-observer_gain_per_s_ * period_s);
  sensor_filtered_n_ += alpha * (sensor.head<3>() - sensor_filtered_n_);
  const double disagreement_n = (sensor_filtered_n_ - observer.head<3>()).norm();
  if (!(disagreement_n > observer_tolerance_n_)) {
    disagreeing_s_ = 0.0;
    return true;
  }
  disagreeing_s_ += period_s;
  if (disagreeing_s_ < kDisagreementS) {
    return true;
  }
  std::snprintf(detail_, sizeof(detail_),
                "the sensor's force (%.1f, %.1f, %.1f N) and the momentum observer's (%.1f, "
                "%.1f, %.1f N) differ by %.1f N for %.2g s (observer_tolerance_n %.3g): a "
                "drifting sensor or a model error; tare out of contact, then reset",
                sensor_filtered_n_.x(), sensor_filtered_n_.y(), sensor_filtered_n_.z(),
                observer.x(), observer.y(), observer.z(), disagreement_n, kDisagreementS,
                observer_tolerance_n_);
  return false;
}

}  // namespace comply::pipeline
