// Hybrid joint impedance, the law of polymetis' HybridJointImpedanceControl (torchcontrol's
// HybridJointSpacePD plus its Coriolis feedforward), which DROID's Franka arms ran:
//
//   tau = (J^T Kx J + Kq)(q_d - q) - (J^T Kxd J + Kqd) dq + C(q, dq) dq + tau_ff
//
// Kq, Kqd: the command's joint stiffness and damping, so they can be streamed like any joint law's.
// Kx, Kxd: plugin parameters, the diagonals of 6x6 gains in the base frame on the end-effector
// Jacobian J (linear rows first); defaults are the ones polymetis ships for the Franka.
//
// The damping acts on dq alone and the command's velocity is ignored: polymetis holds its desired
// joint velocity at zero, and a policy trained under that damping expects the same drag. The
// commanded acceleration is not used either. Gravity is left to the wrapper, as the Franka adds it
// for polymetis.
//
// (J^T Kx J) e is evaluated as J^T (Kx (J e)): the same quantity without forming a dof x dof
// matrix, so step() needs only a 6-entry scratch array on the stack.

#include <cmath>
#include <cstdio>
#include <span>

#include "comply/plugin/controller.hpp"

namespace comply::controllers {
namespace {

constexpr int kTaskAxes = 6;

class HybridJointImpedance final : public JointController {
 public:
  void configure(int dof, const plugin::Parameters& parameters) override {
    plugin::checkDof(dof);
    dof_ = dof;
    readTaskGains(parameters, "Kx", kx_);
    readTaskGains(parameters, "Kxd", kxd_);
  }

  [[nodiscard]] std::uint32_t requiredQuantities() const override {
    return COMPLY_NEED_JACOBIAN | COMPLY_NEED_CORIOLIS;
  }

  comply_status step(const comply_input& input, const comply_joint_command& command,
                     comply_output& output) noexcept override {
    // Task-space wrench Kx J e - Kxd J dq at the end effector, e = q_d - q.
    double wrench[kTaskAxes];
    for (int row = 0; row < kTaskAxes; ++row) {
      double displacement = 0.0;
      double twist = 0.0;
      for (int col = 0; col < dof_; ++col) {
        const double entry = input.jacobian[col * kTaskAxes + row];
        displacement += entry * (command.position[col] - input.position[col]);
        twist += entry * input.velocity[col];
      }
      wrench[row] = kx_[row] * displacement - kxd_[row] * twist;
    }
    for (int i = 0; i < dof_; ++i) {
      double task = 0.0;
      for (int row = 0; row < kTaskAxes; ++row) {
        task += input.jacobian[i * kTaskAxes + row] * wrench[row];
      }
      const double joint = command.stiffness[i] * (command.position[i] - input.position[i]) -
                           command.damping[i] * input.velocity[i];
      output.torque[i] = task + joint + input.coriolis[i] + command.torque_feedforward[i];
    }
    return COMPLY_OK;
  }

 private:
  // Reads one diagonal; absent keeps the default. Refuses anything but 6 finite, non-negative
  // numbers: a negative or NaN gain would make the arm unstable or the torque NaN on every cycle.
  static void readTaskGains(const plugin::Parameters& parameters, const char* name,
                            double (&gains)[kTaskAxes]) {
    if (!parameters.has(name)) {
      return;
    }
    char message[128];
    std::span<const double> values;
    try {
      values = parameters.numbers(name, kTaskAxes);
    } catch (const plugin::ParameterError&) {
      std::snprintf(message, sizeof message,
                    "parameter '%s' must be a list of exactly %d numbers (x y z rx ry rz)", name,
                    kTaskAxes);
      throw plugin::ParameterError(message);
    }
    for (int axis = 0; axis < kTaskAxes; ++axis) {
      const double value = values[static_cast<std::size_t>(axis)];
      if (!std::isfinite(value) || value < 0.0) {
        std::snprintf(message, sizeof message,
                      "parameter '%s' entry %d is %g; gains must be finite and >= 0", name, axis,
                      value);
        throw plugin::ParameterError(message);
      }
      gains[axis] = value;
    }
  }

  int dof_ = 0;
  // polymetis' default_Kx / default_Kxd for the Franka: N/m and N m/rad, N s/m and N m s/rad.
  double kx_[kTaskAxes] = {750.0, 750.0, 750.0, 15.0, 15.0, 15.0};
  double kxd_[kTaskAxes] = {37.0, 37.0, 37.0, 2.0, 2.0, 2.0};
};

}  // namespace
}  // namespace comply::controllers

COMPLY_EXPORT_CONTROLLER(comply::controllers::HybridJointImpedance, "hybrid_joint_impedance")
