// Stage "measure", the wrist sensor: the hardware's force/torque reading (JointState::wrench, the
// wrench on the tool at the TCP, base frame, or TCP frame with wrench_in_tcp) as the law's side
// uses it.
//
//   tool     the declared payload (compensation.payload) is the tool beyond the sensor: its weight
//            at its centre of mass, m g and r x m g about the TCP, comes off every cycle, turned
//            with the tool, so a turning tool reads no change of weight;
//   filter   wrench_sensor.filter_hz: a first-order low-pass on what is left, started from the
//            first reading (a cycle without one holds it);
//   tare     a request (Wrapper::tare) takes what remains, at rest and without contact that is the
//            sensor's own offset, as the zero. The offset is fixed in the sensor, which turns with
//            the TCP: it is kept in the TCP frame and turned into the base frame every cycle.
//
// What is left is the environment's wrench (plus the tool's inertial force while it accelerates,
// which admittance gives back: output_admittance.cpp).

#include <cmath>

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::senseWrench(const JointState& state) noexcept {
  sensor_valid_ = state.wrench_valid && state.wrench.allFinite();
  if (!sensor_valid_) {
    return;
  }
  sensor_seen_.store(true, std::memory_order_relaxed);
  Vector6d reading = state.wrench;
  if (state.wrench_in_tcp) {
    reading.head<3>() = data_.tip_rotation * state.wrench.head<3>();
    reading.tail<3>() = data_.tip_rotation * state.wrench.tail<3>();
  }
  if (parameters_.payload_on_sensor && parameters_.payload.mass_kg > 0.0) {
    const Eigen::Vector3d weight = parameters_.payload.mass_kg * resolved_->model->gravity();
    const Eigen::Vector3d arm = data_.tip_rotation * parameters_.payload.com_in_tip;
    reading.head<3>() -= weight;
    reading.tail<3>() -= arm.cross(weight);
  }
  const double filter_hz = parameters_.wrench_sensor.filter_hz;
  if (filter_hz > 0.0 && sensor_filtered_) {
    const double alpha = 1.0 - std::exp(-2.0 * M_PI * filter_hz * period_s_);
    sensor_untared_ += alpha * (reading - sensor_untared_);
  } else {
    sensor_untared_ = reading;
    sensor_filtered_ = true;
  }
  sensor_wrench_ = sensor_untared_;
  sensor_wrench_.head<3>() -= data_.tip_rotation * tare_in_tcp_.head<3>();
  sensor_wrench_.tail<3>() -= data_.tip_rotation * tare_in_tcp_.tail<3>();
}

void Controller::tare() noexcept {
  if (!sensor_valid_) {
    return;  // a reading missing this cycle: the zero in force stays (the intake refuses a tare
             // on hardware that never gave one)
  }
  tare_in_tcp_.head<3>() = data_.tip_rotation.transpose() * sensor_untared_.head<3>();
  tare_in_tcp_.tail<3>() = data_.tip_rotation.transpose() * sensor_untared_.tail<3>();
  sensor_wrench_.setZero();
}

}  // namespace comply::pipeline
