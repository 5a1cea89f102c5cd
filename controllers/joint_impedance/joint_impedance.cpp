// Joint impedance: tau_i = K_i (q_d,i - q_i) + D_i (dq_d,i - dq_i) + tau_ff,i
//
// Gains, targets and feedforward all come from the command, which the wrapper always hands over
// complete. `max_stiffness` (optional, default unlimited) makes step() refuse stiffer commands; it
// guards against a misconfigured sender and is the plugin-side failure path the tests exercise.
// controllers/joint_impedance_c is the same law in C and must stay bit-identical to this one:
// change both together, keeping the order of operations.

#include <cstdio>
#include <limits>

#include "comply/plugin/controller.hpp"

namespace comply::controllers {
namespace {

class JointImpedance final : public JointController {
 public:
  void configure(int dof, const plugin::Parameters& parameters) override {
    plugin::checkDof(dof);
    dof_ = dof;
    max_stiffness_ = parameters.number("max_stiffness", std::numeric_limits<double>::infinity());
    // Written so that NaN is refused too: a NaN limit would silently disable the check.
    if (!(max_stiffness_ >= 0.0)) {
      throw plugin::ParameterError("parameter 'max_stiffness' must be >= 0");
    }
  }

  comply_status step(const comply_input& input, const comply_joint_command& command,
                     comply_output& output) noexcept override {
    for (int i = 0; i < dof_; ++i) {
      if (command.stiffness[i] > max_stiffness_) {
        std::snprintf(output.message, COMPLY_MESSAGE_CAPACITY,
                      "joint %d: stiffness %g exceeds max_stiffness %g", i, command.stiffness[i],
                      max_stiffness_);
        return COMPLY_ERROR;
      }
    }
    for (int i = 0; i < dof_; ++i) {
      const double spring = command.stiffness[i] * (command.position[i] - input.position[i]);
      const double damper = command.damping[i] * (command.velocity[i] - input.velocity[i]);
      output.torque[i] = spring + damper + command.torque_feedforward[i];
    }
    return COMPLY_OK;
  }

 private:
  int dof_ = 0;
  double max_stiffness_ = std::numeric_limits<double>::infinity();
};

}  // namespace
}  // namespace comply::controllers

COMPLY_EXPORT_CONTROLLER(comply::controllers::JointImpedance, "joint_impedance")
