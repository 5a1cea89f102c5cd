// Stage "measure": the joint state is checked (finite, and not a stale repeat: frozen_state.hpp),
// the model computes what the plugin asked for (and the pose and gravity, which validation and the
// safe state need), the momentum observer and the wrist sensor (wrist_sensor.hpp) read it, the
// plugin input is filled and the measured pose is published for the intake's validation.

#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/plugin_input.hpp"

namespace comply::pipeline {

bool Controller::measure(const JointState& state) noexcept {
  wrist_.invalidate();  // until it reads this cycle's state: a tare needs its reading
  // The robot's own stop comes first, so that the FAULT names it rather than what follows from
  // it (a stream that stands still once the link is lost).
  robot_stopped_ = state.robot_stop != nullptr;
  if (robot_stopped_) {
    enterFault("robot: ", state.robot_stop);
  }
  if (!state.usable(dof_)) {
    enterFault("state: ", "joint state of the wrong size or with NaN/inf position or velocity");
    return false;
  }
  // torque_ is the last cycle's output, computed from the last state. Held at rest after a
  // FAULT's stop, the hardware's own hold (brakes) keeps the state still on purpose.
  const bool braked = safe_hold_.atRest() &&
                      diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
  if (!braked && !robot_stopped_ && frozen_.check(state, state_, torque_, time_s_)) {
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
  if (resolved_->cartesian()) {  // the force stage and the governor read it
    tcp_twist_.noalias() = data_.jacobian.leftCols(dof_) * state_.velocity.head(dof_);
  }
  observe();
  wrist_.sense(state, data_, period_s_);
  safe_hold_.keepGravity(data_);
  fillPluginInput(state_, data_, quantities_, time_s_, period_s_, input_);
  measured_.publishFromSoleWriter(currentPose());
  return true;
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

}  // namespace comply::pipeline
