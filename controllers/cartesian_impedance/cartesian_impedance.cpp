// Cartesian impedance with task-aligned compliance (Albu-Schaeffer et al., "Cartesian impedance
// control of redundant robots", ICRA 2003) and a damped-least-squares nullspace projection:
//
//   e   = [p - p_d; -R phi],  phi = 2 log(eta^-1 eta_d)      pose error, base frame
//   e_v = J dq - v_d                                         twist error, base frame
//   K   = R_task K_task R_task^T (both blocks), D likewise   gains follow the task frame
//   R_task = R_cmd (task_frame_reference: base) or R_tcp R_cmd (tcp: follows the measured tool)
//   tau = J^T (-K e - D e_v + w_ff) + N^T (K_ns (q_ns - q) - D_ns dq) + tau_ff
//   N^T = I - J^T (J^+)^T,  J^+ = J^T (J J^T + lambda^2 I)^-1
//
// Damping is either the command's matrices or, in ratio mode, D = S D_crit S with D_crit from
// double diagonalisation of K against Lambda = (J M^-1 J^T)^-1 and S = sqrt(zeta) on the task
// axes, so damping tracks streamed stiffness on the real inertia rather than a unit mass. The
// diagonalisation works on Lambda^-1 directly and is warm-started from the previous cycle.
// The commanded acceleration is not used by this law. Fixed-capacity storage only.

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "comply/core/capacity.hpp"
#include "comply/core/gains.hpp"
#include "comply/core/rotation.hpp"
#include "comply/plugin/controller.hpp"

namespace comply::controllers {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Quaterniond quaternionFromXyzw(const double* xyzw) {
  return {xyzw[3], xyzw[0], xyzw[1], xyzw[2]};
}

Eigen::Matrix3d rowMajor3x3(const double* values) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(values);
}

void writeMessage(comply_output& output, const char* text) {
  std::snprintf(output.message, COMPLY_MESSAGE_CAPACITY, "%s", text);
}

class CartesianImpedance final : public CartesianController {
 public:
  void configure(int dof, const plugin::Parameters& parameters) override {
    dof_ = dof;
    nullspace_damping_ = parameters.number("nullspace_dls_damping", 0.05);
    inertia_regularisation_ = parameters.number("inertia_regularisation", 1e-6);
    if (!(nullspace_damping_ >= 0.0) || !(inertia_regularisation_ >= 0.0)) {
      throw plugin::ParameterError("nullspace_dls_damping and inertia_regularisation must be >= 0");
    }
    // Ratio-mode damping needs M; a user who never streams ratios can save its computation.
    use_mass_matrix_ = parameters.number("inertia_aware_damping", 1.0) != 0.0;
    const std::string reference = parameters.text("task_frame_reference", "base");
    if (reference != "base" && reference != "tcp") {
      throw plugin::ParameterError("task_frame_reference must be base or tcp, not '" + reference +
                                   "'");
    }
    task_frame_in_tcp_ = reference == "tcp";
  }

  [[nodiscard]] std::uint32_t requiredQuantities() const override {
    return COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN |
           (use_mass_matrix_ ? std::uint32_t{COMPLY_NEED_MASS_MATRIX} : 0U);
  }

  comply_status step(const comply_input& input, const comply_cartesian_command& command,
                     comply_output& output) noexcept override {
    const int n = dof_;
    const Jacobian jacobian =
        Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>(input.jacobian, 6, n);
    const JointVector q = Eigen::Map<const Eigen::VectorXd>(input.position, n);
    const JointVector dq = Eigen::Map<const Eigen::VectorXd>(input.velocity, n);

    // Pose and twist errors in the base frame.
    Vector6d pose_error;
    pose_error.head<3>() = Eigen::Map<const Eigen::Vector3d>(input.tcp_position) -
                           Eigen::Map<const Eigen::Vector3d>(command.position);
    pose_error.tail<3>() = -orientationError(quaternionFromXyzw(input.tcp_orientation),
                                             quaternionFromXyzw(command.orientation));
    const Vector6d twist_error =
        jacobian * dq - Vector6d(Eigen::Map<const Vector6d>(command.twist));

    // Gains from the task frame to the base frame, every cycle. Relative to the measured TCP,
    // the compliance turns with the tool itself, whatever the reference orientation.
    Eigen::Matrix3d task_rotation =
        quaternionFromXyzw(command.task_frame).normalized().toRotationMatrix();
    if (task_frame_in_tcp_) {
      task_rotation =
          quaternionFromXyzw(input.tcp_orientation).normalized().toRotationMatrix() * task_rotation;
    }
    const auto rotate = [&](const double* block) {
      return Eigen::Matrix3d(task_rotation * rowMajor3x3(block) * task_rotation.transpose());
    };
    Matrix6d stiffness = Matrix6d::Zero();
    stiffness.topLeftCorner<3, 3>() = rotate(command.stiffness_translational);
    stiffness.bottomRightCorner<3, 3>() = rotate(command.stiffness_rotational);
    Matrix6d damping = Matrix6d::Zero();
    if (command.damping_mode == COMPLY_DAMPING_RATIO) {
      if (!use_mass_matrix_) {
        writeMessage(output, "damping ratios need inertia_aware_damping: 1");
        return COMPLY_ERROR;
      }
      if (!ratioDamping(input, jacobian, stiffness, task_rotation, command.damping_ratio,
                        damping)) {
        writeMessage(output, "Cartesian inertia not positive definite (singular mass matrix?)");
        return COMPLY_ERROR;
      }
    } else {
      damping.topLeftCorner<3, 3>() = rotate(command.damping_translational);
      damping.bottomRightCorner<3, 3>() = rotate(command.damping_rotational);
    }

    const Vector6d wrench = -stiffness * pose_error - damping * twist_error +
                            Vector6d(Eigen::Map<const Vector6d>(command.wrench_feedforward));
    JointVector torque = jacobian.transpose() * wrench;

    // Nullspace: tau_0 - J^T (J J^T + lambda^2 I)^-1 J tau_0, a 6x6 solve instead of an SVD.
    JointVector nullspace_torque(n);
    for (int i = 0; i < n; ++i) {
      nullspace_torque[i] =
          command.nullspace_stiffness[i] * (command.nullspace_position[i] - q[i]) -
          command.nullspace_damping[i] * dq[i];
    }
    // lazyProduct: a plain coefficient loop; the general matrix product kernel that a
    // dynamic-width operand would select is several times slower at this size.
    const Matrix6d regularised = jacobian.lazyProduct(jacobian.transpose()) +
                                 nullspace_damping_ * nullspace_damping_ * Matrix6d::Identity();
    const Eigen::LDLT<Matrix6d> projector(regularised);
    const Vector6d task_part = projector.solve(jacobian * nullspace_torque);
    torque += nullspace_torque - jacobian.transpose() * task_part;

    for (int i = 0; i < n; ++i) {
      output.torque[i] = torque[i] + command.torque_feedforward[i];
    }
    return COMPLY_OK;
  }

 private:
  /// D = S D_crit S; false when J M^-1 J^T is not positive definite (e.g. M not SPD).
  bool ratioDamping(const comply_input& input, const Jacobian& jacobian, const Matrix6d& stiffness,
                    const Eigen::Matrix3d& task_rotation, const double* ratio,
                    Matrix6d& damping) noexcept {
    const int n = dof_;
    const JointMatrix mass = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(
        input.mass_matrix, n, n, Eigen::OuterStride<>(COMPLY_MAX_DOF));
    const Eigen::LLT<JointMatrix> mass_factor(mass);
    if (mass_factor.info() != Eigen::Success) {
      return false;
    }
    // Column by column: solving all six at once selects the blocked triangular solver, which is
    // slow for a 7x6 right-hand side.
    Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::ColMajor, kMaxDof, 6> mass_inverse_jt(n, 6);
    for (int column = 0; column < 6; ++column) {
      mass_inverse_jt.col(column) = mass_factor.solve(jacobian.row(column).transpose());
    }
    const Matrix6d inverse_inertia =
        jacobian.lazyProduct(mass_inverse_jt) + inertia_regularisation_ * Matrix6d::Identity();
    Matrix6d critical;
    if (!critical_damping_.compute(stiffness, inverse_inertia, critical)) {
      return false;
    }
    Matrix6d ratio_root = Matrix6d::Zero();
    const Eigen::Map<const Vector6d> zeta(ratio);
    ratio_root.topLeftCorner<3, 3>() = task_rotation *
                                       zeta.head<3>().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
                                       task_rotation.transpose();
    ratio_root.bottomRightCorner<3, 3>() = task_rotation *
                                           zeta.tail<3>().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
                                           task_rotation.transpose();
    damping = ratio_root * critical * ratio_root;
    return true;
  }

  // Keeps the eigenbasis of the last cycle: the double diagonalisation then costs 1-2 Jacobi
  // sweeps instead of a full eigen solve.
  CriticalDampingTracker critical_damping_;
  int dof_ = 0;
  double nullspace_damping_ = 0.05;
  double inertia_regularisation_ = 1e-6;
  bool use_mass_matrix_ = true;
  bool task_frame_in_tcp_ = false;  ///< command.task_frame relative to the measured TCP
};

}  // namespace
}  // namespace comply::controllers

COMPLY_EXPORT_CONTROLLER(comply::controllers::CartesianImpedance, "cartesian_impedance")
