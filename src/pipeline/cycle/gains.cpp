// Stage "gains": between the gains the command in force asks for and the gains the law reads,
// the ramps and the energy tank (gain_guard.hpp). Off, it costs one branch and the law reads the
// command in force itself.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::guardGains() noexcept {
  if (!gains_.enabled()) {
    return;
  }
  if (in_force_changed_) {
    gains_.takeCommand(active_);
    in_force_changed_ = false;
  }
  gains_.update(active_, data_, state_, period_s_, torque_clipped_, diagnostics_);
}

}  // namespace comply::pipeline
