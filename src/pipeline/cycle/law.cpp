// Stage "law": the plugin's step on this cycle's input and the command in force. A plugin that
// reports failure or returns a non-finite torque puts the controller in FAULT; its message, if
// any, becomes the fault's reason.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

bool Controller::runLaw() noexcept {
  law_output_.message[0] = '\0';
  if (plugin_->step(input_, busPointer(lawBus()), law_output_) != COMPLY_OK) {
    // A plugin may leave its message unterminated; never read past the buffer.
    law_output_.message[COMPLY_MESSAGE_CAPACITY - 1] = '\0';
    enterFault("plugin: ", law_output_.message[0] != '\0' ? law_output_.message : "step failed");
    return false;
  }
  for (int i = 0; i < dof_; ++i) {
    torque_[i] = law_output_.torque[i];
  }
  law_torque_ = torque_;  // kept apart for a saturation that scales the law's torque alone
  if (!torque_.allFinite()) {
    enterFault("plugin: ", "non-finite torque");
    return false;
  }
  return true;
}

}  // namespace comply::pipeline
