// Stages "commands" and "watchdog": every message the intake queued since the last cycle is taken
// in order (commands merged by their field mask into the command in force, reset requests noted, a
// tare taken), and the watchdog applies the timeout policy to the same command in force, so the
// reference rules live in one place: here, on the bus the law reads.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::takeCommands() noexcept {
  bool changed = false;
  for (const IntakeMessage* message = intake_.front(); message != nullptr;
       message = intake_.front()) {
    if (message->type == IntakeMessage::Type::kTare) {
      tare();
    } else if (message->type == IntakeMessage::Type::kReset) {
      // Only a fault present when the request arrives can be reset: a request must not stay armed
      // and clear a later fault unasked.
      reset_pending_ = diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
    } else if (message->type == IntakeMessage::Type::kChunk) {
      if (chunks_.playing()) {
        (void)chunks_.play(time_s_, active_);  // the running chunk's reference at this time
      }
      chunks_.start(message->chunk_slot, active_, time_s_);
      // Taken, whatever happens to it next (FAULT stops it at once): its stamp is in force.
      std::visit([this](auto& bus) noexcept { bus.stamp_s = chunks_.stamp(); }, active_);
      changed = true;
    } else {
      takeCommand(message->command);
      changed = true;
    }
    intake_.pop();
  }
  if (changed) {
    last_command_time_s_ = time_s_;
    watchdog_expired_ = false;
  }
  const bool chunk_ran = chunks_.playing();
  playChunk();
  if (changed || chunk_ran) {
    publishInForce();
  }
}

void Controller::takeCommand(const CommandBus& command) noexcept {
  const std::uint32_t sets =
      std::visit([](const auto& bus) noexcept { return bus.fields; }, command);
  if ((sets & chunks_.fields()) != 0) {
    (void)chunks_.play(time_s_, active_);
    chunks_.stop();
    stopMotion(active_);
  }
  mergeInto(active_, command);
}

void Controller::playChunk() noexcept {
  if (!chunks_.playing()) {
    return;
  }
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault) {
    // A reset resumes from the reference where the fault left it, not from wherever the chunk
    // would have carried it meanwhile.
    chunks_.stop();
    stopMotion(active_);
    return;
  }
  (void)chunks_.play(time_s_, active_);
  // A chunk is a command that lasts: the watchdog counts from its end.
  last_command_time_s_ = time_s_;
  watchdog_expired_ = false;
}

void Controller::watchdog() noexcept {
  const double timeout_s = parameters_.command_timeout_s;
  if (watchdog_expired_ || timeout_s <= 0.0 || time_s_ - last_command_time_s_ < timeout_s) {
    return;
  }
  watchdog_expired_ = true;
  chunks_.stop();
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
