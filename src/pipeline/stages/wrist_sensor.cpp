#include "comply/pipeline/wrist_sensor.hpp"

#include <cmath>

namespace comply::pipeline {

WristSensor::WristSensor(const ResolvedController& resolved) noexcept : resolved_(resolved) {
  const CycleParameters& parameters = resolved.parameters;
  if (parameters.payload_on_sensor && parameters.payload.mass_kg > 0.0) {
    tool_weight_n_ = parameters.payload.mass_kg * resolved.model->gravity();
  }
}

void WristSensor::sense(const JointState& state, const model::Data& data,
                        double period_s) noexcept {
  valid_ = state.wrench_valid && state.wrench.allFinite();
  if (!valid_) {
    return;
  }
  seen_.store(true, std::memory_order_relaxed);
  const CycleParameters& parameters = resolved_.parameters;
  Vector6d reading = state.wrench;
  if (state.wrench_in_tcp) {
    reading.head<3>() = data.tip_rotation * state.wrench.head<3>();
    reading.tail<3>() = data.tip_rotation * state.wrench.tail<3>();
  }
  if (parameters.payload_on_sensor && parameters.payload.mass_kg > 0.0) {
    const Eigen::Vector3d arm = data.tip_rotation * parameters.payload.com_in_tip;
    reading.head<3>() -= tool_weight_n_;
    reading.tail<3>() -= arm.cross(tool_weight_n_);
  }
  const double filter_hz = parameters.wrench_sensor.filter_hz;
  if (filter_hz > 0.0 && filtered_) {
    const double alpha = 1.0 - std::exp(-2.0 * M_PI * filter_hz * period_s);
    untared_ += alpha * (reading - untared_);
  } else {
    untared_ = reading;
    filtered_ = true;
  }
  wrench_ = untared_;
  wrench_.head<3>() -= data.tip_rotation * tare_in_tcp_.head<3>();
  wrench_.tail<3>() -= data.tip_rotation * tare_in_tcp_.tail<3>();
}

void WristSensor::tare(const model::Data& data) noexcept {
  if (!valid_) {
    return;  // a reading missing this cycle: the zero in force stays (the intake refuses a tare
             // on hardware that never gave one)
  }
  tare_in_tcp_.head<3>() = data.tip_rotation.transpose() * untared_.head<3>();
  tare_in_tcp_.tail<3>() = data.tip_rotation.transpose() * untared_.tail<3>();
  wrench_.setZero();
}

}  // namespace comply::pipeline
