// Stages "commands" and "watchdog": every message the intake queued since the last cycle is taken
// in order (commands merged by their field mask into the command in force, reset requests noted, a
// tare taken), and the watchdog (command_watchdog.hpp) applies the timeout policy to the same
// command in force, so the reference rules live in one place: here, on the bus the law reads.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::takeCommands() noexcept {
  bool changed = false;
  for (const IntakeMessage* message = intake_.front(); message != nullptr;
       message = intake_.front()) {
    if (message->type == IntakeMessage::Type::kTare) {
      wrist_.tare(data_);
    } else if (message->type == IntakeMessage::Type::kReset) {
      changed = takeReset(message->id.sequence) || changed;
    } else if (message->type == IntakeMessage::Type::kDropChunk) {
      changed = dropWaitingChunk(message->id.sequence) || changed;
    } else if (message->type == IntakeMessage::Type::kChunk) {
      takeChunk(*message);
      changed = true;
    } else {
      takeCommand(*message);
      changed = true;
    }
    intake_.pop();
  }
  if (changed) {
    watchdog_.heard(time_s_);
  }
  const bool chunk_ran = chunks_.playing() || chunks_.waiting();
  playChunk();
  if (changed || chunk_ran) {
    publishInForce();
  }
}

bool Controller::takeReset(std::uint64_t number) noexcept {
  // A chunk still waiting for its start does not outlive a reset.
  const bool dropped = dropWaitingChunk(0);
  // Only a fault present when the request arrives can be reset: a request must not stay armed
  // and clear a later fault unasked. So with the reflex's hold.
  reset_pending_ = diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
  reset_number_ = number;
  const bool reflex_held = reflex_.latched();
  if (!reset_pending_) {
    // Full: no one reads them.
    (void)reset_results_.push(
        {number, reflex_held ? ResetResult::End::kLeftReflex : ResetResult::End::kNoFault});
  }
  if (reset_pending_ || reflex_held) {
    // The command in force may be what caused the fault or the reflex (a target the arm could not
    // reach, a feedforward it could not carry, a motion into something), and the arm has moved
    // since: the measured pose is held, with the gains and task frame in force, and the reflex's
    // thresholds are the file's again. Here, so that what the intake queued after the request
    // builds on it (resumeAfterReset() restarts the stages if a FAULT's reset is taken; under
    // the reflex's hold the law kept running, and nothing needs restarting).
    chunks_.stop();
    holdMeasured(active_, currentPose());
    rearmReflex();
  }
  return dropped || reset_pending_ || reflex_held;
}

bool Controller::dropWaitingChunk(std::uint64_t sequence) noexcept {
  if (!chunks_.dropWaiting(sequence, time_s_)) {
    return false;
  }
  // Where the blend toward it had got, at rest; a force axis ends holding the arm where it is.
  anchorForceAxes(active_, currentPose());
  stopMotion(active_);
  return true;
}

void Controller::takeCommand(const IntakeMessage& message) noexcept {
  if (reflex_.latched()) {
    // Accepted before the intake saw the trip: taken (its outcome is settled) without effect.
    id_in_force_ = message.id;
    return;
  }
  const std::uint32_t sets =
      std::visit([](const auto& bus) noexcept { return bus.fields; }, message.command);
  const bool stops_chunk = (sets & chunks_.fields()) != 0;
  if (stops_chunk) {
    (void)chunks_.play(time_s_, active_);
    chunks_.stop();
  }
  // A force axis this command (or the chunk's stop) ends holds the arm where it is: the reference
  // along the axes in force is the measured pose (force_axes.hpp), unless the command sets one.
  anchorForceAxes(active_, currentPose());
  if (stops_chunk) {
    stopMotion(active_);
  }
  mergeInto(active_, message.command);
  id_in_force_ = message.id;
}

void Controller::takeChunk(const IntakeMessage& message) noexcept {
  if (reflex_.latched()) {
    chunks_.release(message.chunk_slot);  // as a command the intake took before it saw the trip
    id_in_force_ = message.id;
    return;
  }
  if (chunks_.playing()) {
    (void)chunks_.play(time_s_, active_);  // the running chunk's reference at this time
  }
  if (!chunks_.take(message.chunk_slot, active_, time_s_)) {
    // It waits for its takeover time; until then the running chunk and its number stay in force.
    waiting_chunk_id_ = message.id;
    return;
  }
  // Taken, whatever happens to it next (FAULT stops it at once): its stamp is in force.
  std::visit([this](auto& bus) noexcept { bus.stamp_s = chunks_.stamp(); }, active_);
  id_in_force_ = message.id;
}

void Controller::playChunk() noexcept {
  if (!chunks_.playing() && !chunks_.waiting()) {
    return;
  }
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault) {
    // The chunk ends with the fault; a reset then holds the measured pose (takeReset()).
    chunks_.stop();
    anchorForceAxes(active_, currentPose());
    stopMotion(active_);
    return;
  }
  if (chunks_.takeOverDue(time_s_, active_) != 0) {
    std::visit([this](auto& bus) noexcept { bus.stamp_s = chunks_.stamp(); }, active_);
    id_in_force_ = waiting_chunk_id_;
  }
  (void)chunks_.play(time_s_, active_);
  // A chunk is a command that lasts: the watchdog counts from its end.
  watchdog_.heard(time_s_);
}

void Controller::resumeAfterReset() noexcept {
  // The command in force holds the measured pose since the request (takeReset()); the stages that
  // integrate start again from here.
  frozen_.reset();  // it did not judge the state the hardware's hold kept still
  publishInForce();
  guard_.reset();
  watchdog_.heard(time_s_);
  sensor_check_.restart();  // a rest check that failed stays armed: this cycle checks again
  gains_.reset(active_, data_, state_, diagnostics_);
  force_.reset();
  force_active_ = false;
  safe_hold_.reset();
}

void Controller::watchdog() noexcept {
  if (!watchdog_.expires(time_s_)) {
    return;
  }
  chunks_.stop();
  diagnostics_.watchdog_timeouts.fetch_add(1, std::memory_order_relaxed);
  if (parameters_.timeout_behavior == TimeoutBehavior::kReanchor) {
    if (state_usable_) {
      seedFromMeasured(active_, currentPose());
    }
  } else {
    // Holding the last reference means holding its pose: a velocity reference would keep pulling.
    // The force axes end holding the measured pose along them, not springing back to a reference
    // the arm has left (force_axes.hpp).
    anchorForceAxes(active_, currentPose());
    stopMotion(active_);
  }
  publishInForce();
}

}  // namespace comply::pipeline
