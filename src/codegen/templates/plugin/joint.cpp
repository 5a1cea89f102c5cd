// my_law: joint impedance, tau_i = K_i (q_ref,i - q_i) + D_i (dq_ref,i - dq_i) + tau_ff,i.
//
// A starting point written by `comply plugin new`: gains, targets and feedforward come from the
// command, which the wrapper hands over complete every cycle (its initial gains until a sender
// sets others). Change step() into your law; configure() is where plugin_parameters arrive.

#include "comply/plugin/controller.hpp"

namespace {

class MyLaw final : public comply::JointController {
 public:
  void configure(int dof, const comply::plugin::Parameters& parameters) override {
    (void)parameters;
    comply::plugin::checkDof(dof);
    dof_ = dof;
  }

  comply_status step(const comply_input& input, const comply_joint_command& command,
                     comply_output& output) noexcept override {
    const double* q = input.position;
    const double* dq = input.velocity;
    const double* q_ref = command.position;
    const double* dq_ref = command.velocity;
    for (int i = 0; i < dof_; ++i) {
      const double spring = command.stiffness[i] * (q_ref[i] - q[i]);
      const double damper = command.damping[i] * (dq_ref[i] - dq[i]);
      output.torque[i] = spring + damper + command.torque_feedforward[i];
    }
    return COMPLY_OK;
  }

 private:
  int dof_ = 0;
};

}  // namespace

COMPLY_EXPORT_CONTROLLER(MyLaw, "my_law")
