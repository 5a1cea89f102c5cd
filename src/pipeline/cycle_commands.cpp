// Stages "commands" and "watchdog": every message the intake queued since the last cycle is taken
// in order (commands merged by their field mask into the command in force, reset requests noted),
// and the watchdog applies the timeout policy to the same command in force, so the reference rules
// live in one place: here, on the bus the law reads.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::takeCommands() noexcept {
  bool changed = false;
  for (const IntakeMessage* message = intake_.front(); message != nullptr;
       message = intake_.front()) {
    if (message->type == IntakeMessage::Type::kReset) {
      // Only a fault present when the request arrives can be reset: a request must not stay armed
      // and clear a later fault unasked.
      reset_pending_ = diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
    } else {
      mergeInto(active_, message->command);
      changed = true;
    }
    intake_.pop();
  }
  if (changed) {
    last_command_time_s_ = time_s_;
    watchdog_expired_ = false;
    publishInForce();
  }
}

void Controller::watchdog() noexcept {
  const double timeout_s = parameters_.command_timeout_s;
  if (watchdog_expired_ || timeout_s <= 0.0 || time_s_ - last_command_time_s_ < timeout_s) {
    return;
  }
  watchdog_expired_ = true;
  diagnostics_.watchdog_timeouts.fetch_add(1, std::memory_order_relaxed);
  if (parameters_.timeout_behavior == TimeoutBehavior::kReanchor) {
    if (state_usable_) {
      seedFromMeasured(active_, currentPose());
    }
  } else {
    // Holding the last reference means holding its pose: a velocity reference would keep pulling.
    stopMotion(active_);
  }
  publishInForce();
}

}  // namespace comply::pipeline
