// Stage "measure": the joint state is checked (finite, and not a stale repeat), the model computes
// what the plugin asked for (and the pose and gravity, which validation and the safe state need),
// the plugin input is filled and the measured pose is published for the intake's validation.

#include <cstring>

#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/plugin_input.hpp"

namespace comply::pipeline {

bool Controller::measure(const JointState& state) noexcept {
  sensor_valid_ = false;  // until senseWrench() reads this cycle's state: a tare needs its reading
  if (!state.usable(dof_)) {
    enterFault("state: ", "joint state of the wrong size or with NaN/inf position or velocity");
    return false;
  }
  if (stateFrozen(state)) {
    enterFault("state: ",
               state.sequence_valid
                   ? "the driver's sample counter has not advanced for frozen_state_timeout_s: a "
                     "stale sensor stream"
                   : "joint state unchanged bit for bit for frozen_state_timeout_s while the "
                     "torque changed or its own velocity should have moved it: a stale sensor "
                     "stream");
    return false;
  }
  const std::span<const double> q(state.position.data(), static_cast<std::size_t>(dof_));
  const std::span<const double> dq(state.velocity.data(), static_cast<std::size_t>(dof_));
  if (model::update(*resolved_->model, data_, q, dq, quantities_) != model::UpdateStatus::kOk) {
    enterFault("model: ", "update failed");
    return false;
  }
  state_ = state;
  observe();
  senseWrench(state);
  keepHoldingGravity();
  fillPluginInput(state_, data_, quantities_, time_s_, period_s_, input_);
  measured_.publishFromSoleWriter(currentPose());
  return true;
}

namespace {

/// Bit for bit: a NaN effort (a robot without torque sensing) repeats as well as a number.
bool sameBits(const JointVector& a, const JointVector& b) noexcept {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

}  // namespace

bool Controller::stateFrozen(const JointState& state) noexcept {
  if (state.sequence_valid) {
    return sequenceStale(state);
  }
  const bool repeated = sameBits(state.position, state_.position) &&
                        sameBits(state.velocity, state_.velocity) &&
                        sameBits(state.effort, state_.effort);
  if (!repeated || parameters_.frozen_state_timeout_s <= 0.0) {
    repeated_cycles_ = 0;
    state_frozen_ = false;
    return false;
  }
  if (repeated_cycles_++ == 0) {
    // torque_ is the last cycle's output, computed from this same state.
    repeated_since_s_ = time_s_;
    torque_when_repeated_ = torque_;
  }
  if (state_frozen_) {
    return true;
  }
  if (time_s_ - repeated_since_s_ < parameters_.frozen_state_timeout_s) {
    return false;
  }
  // Stale either way: the torque moved and the state did not answer, or the state reports a
  // velocity under which its own position would have moved, and it did not (an arm pushed by
  // hand while its stream repeats a moving sample: the law's torque need not change for that).
  const double unmoved_s = time_s_ - repeated_since_s_;
  state_frozen_ =
      (torque_ - torque_when_repeated_).cwiseAbs().maxCoeff() > kFrozenStateTorqueChangeNm ||
      state.velocity.cwiseAbs().maxCoeff() * unmoved_s > kFrozenStateMotionRad;
  return state_frozen_;
}

bool Controller::sequenceStale(const JointState& state) noexcept {
  // The driver's counter decides: a new sample is fresh however alike it is (an arm at rest, or
  // pressing on a wall, repeats its encoders), an old one is stale however the torque moves.
  if (parameters_.frozen_state_timeout_s <= 0.0 || !sequence_seen_ ||
      state.sequence != last_sequence_) {
    last_sequence_ = state.sequence;
    sequence_seen_ = true;
    sequence_since_s_ = time_s_;
    state_frozen_ = false;
    return false;
  }
  state_frozen_ = time_s_ - sequence_since_s_ >= parameters_.frozen_state_timeout_s;
  return state_frozen_;
}

void Controller::observe() noexcept {
  if (!observer_.enabled()) {
    return;
  }
  // The torque that acted over the period that ended: measured, or what the last cycle wrote
  // (comply's share, plus the gravity a robot that compensates it adds itself).
  if (parameters_.observer.measured_torque && state_.effort.allFinite()) {
    scratch_ = state_.effort;
  } else {
    scratch_ = torque_;
    if (parameters_.hardware_compensates_gravity) {
      scratch_ += data_.gravity.head(dof_);
    }
  }
  // A declared payload is part of the arm, not of its environment: the torque holding it up is
  // not pushing anything (its inertia stays unmodelled).
  if (parameters_.payload_compensation) {
    scratch_ -= data_.payload_gravity.head(dof_);
  }
  observer_.update(state_.velocity, scratch_, data_, period_s_);
}

void Controller::keepHoldingGravity() noexcept {
  // A robot that compensates gravity itself holds its own weight; adding it here would lift it.
  if (parameters_.hardware_compensates_gravity) {
    hold_gravity_.setZero();
  } else {
    hold_gravity_ = data_.gravity.head(dof_);
  }
  if (parameters_.payload_compensation) {
    hold_gravity_ += data_.payload_gravity.head(dof_);
  }
}

}  // namespace comply::pipeline
