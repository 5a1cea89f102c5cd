// my_law: Cartesian impedance, a spring-damper on the TCP mapped to the joints through J^T:
//
//   F   = K e + D (v_ref - J dq) + w_ff,  e = [p_ref - p; rotation vector from the TCP to q_ref]
//   tau = J^T F + tau_ff
//
// A starting point written by `comply plugin new`. Targets and gains come from the command, which
// the wrapper hands over complete every cycle. To stay short it applies the gains in the base frame
// (the command's task_frame is ignored), has no nullspace term (a redundant arm may drift in its
// nullspace; the reference cartesian_impedance plugin adds one) and, in damping-ratio mode, damps
// a unit mass (D_ii = 2 zeta_i sqrt(K_ii)) for lack of an inertia model.

#include <array>
#include <cmath>

#include "comply/plugin/controller.hpp"

namespace {

using Vector6 = std::array<double, 6>;

/// Pose error in the base frame. The rotation part is 2 vec(q_ref q^-1) (quaternions x y z w), the
/// rotation vector for small errors; its sign picks the shorter way round.
Vector6 poseError(const comply_input& input, const comply_cartesian_command& command) {
  const double* a = command.orientation;
  const double* q = input.tcp_orientation;
  const double b[4] = {-q[0], -q[1], -q[2], q[3]};
  const double w = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
  const double sign = w < 0.0 ? -2.0 : 2.0;
  Vector6 error{};
  for (int i = 0; i < 3; ++i) {
    error[i] = command.position[i] - input.tcp_position[i];
  }
  error[3] = sign * (a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1]);
  error[4] = sign * (a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0]);
  error[5] = sign * (a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3]);
  return error;
}

/// force += K e + D e_v for one 3x3 block (row-major); ratio mode damps a unit mass per axis.
void springDamper(const double* stiffness, const double* damping, const double* ratio,
                  bool use_ratio, const double* e, const double* e_v, double* force) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      force[r] += stiffness[r * 3 + c] * e[c];
      if (!use_ratio) {
        force[r] += damping[r * 3 + c] * e_v[c];
      }
    }
    if (use_ratio) {
      force[r] += 2.0 * ratio[r] * std::sqrt(std::abs(stiffness[r * 3 + r])) * e_v[r];
    }
  }
}

class MyLaw final : public comply::CartesianController {
 public:
  void configure(int dof, const comply::plugin::Parameters& parameters) override {
    (void)parameters;
    comply::plugin::checkDof(dof);
    dof_ = dof;
  }

  [[nodiscard]] std::uint32_t requiredQuantities() const override {
    return COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN;
  }

  comply_status step(const comply_input& input, const comply_cartesian_command& command,
                     comply_output& output) noexcept override {
    const double* jacobian = input.jacobian;  // 6 x dof, column-major
    const bool use_ratio = command.damping_mode == COMPLY_DAMPING_RATIO;
    const Vector6 error = poseError(input, command);
    Vector6 twist_error{};
    Vector6 force{};
    for (int r = 0; r < 6; ++r) {
      twist_error[r] = command.twist[r];
      force[r] = command.wrench_feedforward[r];
    }
    for (int j = 0; j < dof_; ++j) {
      for (int r = 0; r < 6; ++r) {
        twist_error[r] -= jacobian[j * 6 + r] * input.velocity[j];
      }
    }
    springDamper(command.stiffness_translational, command.damping_translational,
                 command.damping_ratio, use_ratio, error.data(), twist_error.data(), force.data());
    springDamper(command.stiffness_rotational, command.damping_rotational,
                 command.damping_ratio + 3, use_ratio, error.data() + 3, twist_error.data() + 3,
                 force.data() + 3);
    for (int j = 0; j < dof_; ++j) {
      double torque = command.torque_feedforward[j];
      for (int r = 0; r < 6; ++r) {
        torque += jacobian[j * 6 + r] * force[r];
      }
      output.torque[j] = torque;
    }
    return COMPLY_OK;
  }

 private:
  int dof_ = 0;
};

}  // namespace

COMPLY_EXPORT_CONTROLLER(MyLaw, "my_law")
