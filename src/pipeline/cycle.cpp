// Controller::update(): the control cycle as a table of contents. Each stage is a member function
// in its own file; this one only says in which order they run and where a failure leads.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

CycleStatus Controller::update(const JointState& state, double period_s,
                               std::span<double> torque) noexcept {
  advanceClock(period_s);
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kInactive) {
    return CycleStatus::kInactive;
  }
  if (static_cast<int>(torque.size()) < dof_) {
    enterFault("output: ", "torque buffer smaller than the number of joints");
    return CycleStatus::kFault;
  }
  state_usable_ = measure(state);  // cycle_measure.cpp; FAULT on a bad state
  if (state_usable_) {
    guardMotion();  // cycle_guard.cpp; FAULT on a runaway (the state stays usable for the hold)
  }
  takeCommands();  // cycle_commands.cpp
  watchdog();      // cycle_commands.cpp
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault) {
    // A reset is consumed either way: one refused for a bad state is not carried to a later cycle.
    const bool reset = reset_pending_ && state_usable_;
    reset_pending_ = false;
    if (!reset) {
      return hold(torque);  // cycle_torque.cpp
    }
    diagnostics_.state.store(WrapperState::kActive, std::memory_order_relaxed);
  }
  reset_pending_ = false;
  guardGains();     // cycle_gains.cpp
  applyForce();     // cycle_force.cpp
  if (!runLaw()) {  // cycle_law.cpp
    return hold(torque);
  }
  compensate();                          // cycle_torque.cpp
  if (!shape() || !guardSaturation()) {  // cycle_torque.cpp; cycle_guard.cpp
    return hold(torque);
  }
  return write(torque);
}

}  // namespace comply::pipeline
