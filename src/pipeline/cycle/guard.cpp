// Stage "guard": the stability guard's rules (stability_guard.hpp) at this cycle's state, and its
// saturation rule on the shaped torque; a broken rule is a FAULT naming the joint and the number.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

bool Controller::guardMotion() noexcept {
  if (!guard_.checkMotion(state_, period_s_)) {
    enterFault("stability guard: ", guard_.detail());
    return false;
  }
  // The energy rule judges the law's command of the last cycle, and only while active: after a
  // FAULT the hold, not the law, moves the arm.
  if (diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kActive &&
      !guard_.checkEnergy(state_, lawBus(), period_s_)) {
    enterFault("stability guard: ", guard_.detail());
    return false;
  }
  return true;
}

bool Controller::guardSaturation() noexcept {
  if (!guard_.checkSaturation(torque_, period_s_)) {
    enterFault("stability guard: ", guard_.detail());
    return false;
  }
  return true;
}

}  // namespace comply::pipeline
