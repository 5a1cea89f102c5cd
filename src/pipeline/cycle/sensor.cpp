// Stage "sensor": whether the wrist sensor's reading can be trusted (sensor_check.hpp), after the
// commands and a reset are taken and before anything the reading can move (the force stage, an
// admittance's virtual arm): the first reading at rest after activation, or at the reset after a
// failed check, near zero; and, where the momentum observer runs, in agreement with it.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

bool Controller::checkSensor() noexcept {
  if (!wrist_.valid()) {
    return true;  // no reading this cycle: the check waits for one
  }
  if (!sensor_check_.checkAtRest(wrist_.wrench(), state_.velocity)) {
    enterFault("wrist sensor: ", sensor_check_.detail());
    return false;
  }
  if (sensor_check_.comparesWithObserver() &&
      !sensor_check_.compareWithObserver(wrist_.wrench(), observer_.wrench(), period_s_)) {
    enterFault("wrist sensor: ", sensor_check_.detail());
    return false;
  }
  return true;
}

}  // namespace comply::pipeline
