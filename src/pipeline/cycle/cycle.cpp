// The control cycle as two tables of contents (controller.hpp): cycle() for the drives around
// update(), the law's cycle. Each stage lives in its own file; this one only says in which order
// they run and where a failure leads.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

bool Controller::cycle(const JointState& state, double period_s,
                       ActuatorCommand& command) noexcept {
  command.mode = output_stage_.mode();
  const std::span<double> torque(command.effort.data(),
                                 static_cast<std::size_t>(command.effort.size()));
  const JointState& law_state = output_stage_.lawState(state);  // output/output_stage.cpp
  const CycleStatus status = update(law_state, period_s, torque);
  return output_stage_.write(status, *this, state, period_s, command);
}

CycleStatus Controller::update(const JointState& state, double period_s,
                               std::span<double> torque) noexcept {
  chunks_.clearEvents();  // the observer has read the last cycle's
  advanceClock(period_s);
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kInactive) {
    return CycleStatus::kInactive;
  }
  if (static_cast<int>(torque.size()) < dof_) {
    enterFault("output: ", "torque buffer smaller than the number of joints");
    return CycleStatus::kFault;
  }
  state_usable_ = measure(state);  // measure.cpp; FAULT on a bad state
  if (state_usable_) {
    guardMotion();  // guard.cpp; FAULT on a runaway (the state stays usable for the hold)
  }
  takeCommands();  // commands.cpp
  watchdog();      // commands.cpp
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault) {
    // A reset is consumed either way: one refused for a bad state is not carried to a later cycle.
    const bool reset = reset_pending_ && state_usable_ && !robot_stopped_;
    if (reset_pending_) {
      const ResetResult::End end = reset            ? ResetResult::End::kLeftFault
                                   : robot_stopped_ ? ResetResult::End::kRobotStopped
                                                    : ResetResult::End::kStateUnusable;
      (void)reset_results_.push({reset_number_, end});
    }
    reset_pending_ = false;
    if (!reset) {
      return hold(torque);  // torque.cpp
    }
    resumeAfterReset();  // commands.cpp: the measured pose held, never the fault's target
    diagnostics_.state.store(WrapperState::kActive, std::memory_order_relaxed);
  }
  reset_pending_ = false;
  if (!checkSensor()) {  // sensor.cpp; before anything the reading can move
    return hold(torque);
  }
  if (!checkContact()) {  // reflex.cpp; hold and retreat write the command in force
    return hold(torque);
  }
  guardGains();     // gains.cpp
  applyForce();     // force.cpp
  limitToWalls();   // walls.cpp
  if (!runLaw()) {  // law.cpp
    return hold(torque);
  }
  compensate();                          // torque.cpp
  govern();                              // torque.cpp
  limitContactSpeed();                   // contact_speed.cpp
  brakeAtWalls();                        // walls.cpp
  if (!shape() || !guardSaturation()) {  // torque.cpp; guard.cpp
    return hold(torque);
  }
  return write(torque);
}

}  // namespace comply::pipeline
