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
//
// The law is one template over the DOF: configure() picks the instance compiled for 6 or 7 joints
// (every product and factorisation then has sizes known to the compiler) or the dynamic one for
// any other count up to the capacity.

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "comply/core/capacity.hpp"
#include "comply/core/gains.hpp"
#include "comply/core/rotation.hpp"
#include "comply/plugin/controller.hpp"
#include "small_kernels.hpp"

namespace comply::controllers {
namespace {

Eigen::Quaterniond quaternionFromXyzw(const double* xyzw) {
  return {xyzw[3], xyzw[0], xyzw[1], xyzw[2]};
}

Eigen::Matrix3d rowMajor3x3(const double* values) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(values);
}

void writeMessage(comply_output& output, const char* text) {
  std::snprintf(output.message, COMPLY_MESSAGE_CAPACITY, "%s", text);
}

/// Block-diagonal 6x6 from two 3x3 blocks given row-major in the command, turned into the base
/// frame by `rotation` unless the task frame is the base frame.
Matrix6d blockDiagonal(const double* top, const double* bottom, const Eigen::Matrix3d& rotation,
                       bool rotated) {
  Matrix6d result = Matrix6d::Zero();
  if (rotated) {
    result.topLeftCorner<3, 3>() = rotation * rowMajor3x3(top) * rotation.transpose();
    result.bottomRightCorner<3, 3>() = rotation * rowMajor3x3(bottom) * rotation.transpose();
  } else {
    result.topLeftCorner<3, 3>() = rowMajor3x3(top);
    result.bottomRightCorner<3, 3>() = rowMajor3x3(bottom);
  }
  return result;
}

/// D = S D_crit S with S = R diag(sqrt(zeta)) R^T on each block; equal ratios make S a scalar.
Matrix6d applyRatios(const Matrix6d& critical, const double* ratio,
                     const Eigen::Matrix3d& rotation) {
  const Eigen::Map<const Vector6d> zeta(ratio);
  const Vector6d root = zeta.cwiseMax(0.0).cwiseSqrt();
  if ((root.array() == root[0]).all()) {
    return (root[0] * root[0]) * critical;
  }
  Matrix6d ratio_root = Matrix6d::Zero();
  ratio_root.topLeftCorner<3, 3>() = rotation * root.head<3>().asDiagonal() * rotation.transpose();
  ratio_root.bottomRightCorner<3, 3>() =
      rotation * root.tail<3>().asDiagonal() * rotation.transpose();
  return ratio_root * critical * ratio_root;
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
    step_ = dof == 7   ? &CartesianImpedance::stepSized<7>
            : dof == 6 ? &CartesianImpedance::stepSized<6>
                       : &CartesianImpedance::stepSized<Eigen::Dynamic>;
  }

  [[nodiscard]] std::uint32_t requiredQuantities() const override {
    return COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN |
           (use_mass_matrix_ ? std::uint32_t{COMPLY_NEED_MASS_MATRIX} : 0U);
  }

  comply_status step(const comply_input& input, const comply_cartesian_command& command,
                     comply_output& output) noexcept override {
    return (this->*step_)(input, command, output);
  }

 private:
  using Step = comply_status (CartesianImpedance::*)(const comply_input&,
                                                     const comply_cartesian_command&,
                                                     comply_output&) noexcept;

  template <int N>
  comply_status stepSized(const comply_input& input, const comply_cartesian_command& command,
                          comply_output& output) noexcept {
    using Joints = Sized<N>;
    const int n = dof_;
    const typename Joints::Jacobian jacobian =
        Eigen::Map<const Eigen::Matrix<double, 6, N>>(input.jacobian, 6, n);
    const typename Joints::Vector q =
        Eigen::Map<const Eigen::Matrix<double, N, 1>>(input.position, n);
    const typename Joints::Vector dq =
        Eigen::Map<const Eigen::Matrix<double, N, 1>>(input.velocity, n);

    // Pose and twist errors in the base frame.
    Vector6d pose_error;
    pose_error.head<3>() = Eigen::Map<const Eigen::Vector3d>(input.tcp_position) -
                           Eigen::Map<const Eigen::Vector3d>(command.position);
    pose_error.tail<3>() = -orientationError(quaternionFromXyzw(input.tcp_orientation),
                                             quaternionFromXyzw(command.orientation));
    const Vector6d twist_error =
        jacobian.lazyProduct(dq) - Vector6d(Eigen::Map<const Vector6d>(command.twist));

    // Gains from the task frame to the base frame, every cycle. Relative to the measured TCP,
    // the compliance turns with the tool itself, whatever the reference orientation.
    const Eigen::Quaterniond task_frame = quaternionFromXyzw(command.task_frame);
    const bool rotated = task_frame_in_tcp_ || task_frame.vec().squaredNorm() != 0.0;
    Eigen::Matrix3d task_rotation = Eigen::Matrix3d::Identity();
    if (rotated) {
      task_rotation = task_frame.normalized().toRotationMatrix();
    }
    if (task_frame_in_tcp_) {
      task_rotation =
          quaternionFromXyzw(input.tcp_orientation).normalized().toRotationMatrix() * task_rotation;
    }
    const Matrix6d stiffness = blockDiagonal(command.stiffness_translational,
                                             command.stiffness_rotational, task_rotation, rotated);
    Matrix6d damping;
    if (command.damping_mode == COMPLY_DAMPING_RATIO) {
      if (!use_mass_matrix_) {
        writeMessage(output, "damping ratios need inertia_aware_damping: 1");
        return COMPLY_ERROR;
      }
      Matrix6d inverse_inertia;
      Matrix6d critical;
      if (!inverseCartesianInertia<N>(input.mass_matrix, jacobian, inverse_inertia) ||
          !critical_damping_.compute(
              stiffness, inverse_inertia + inertia_regularisation_ * Matrix6d::Identity(),
              critical)) {
        writeMessage(output, "Cartesian inertia not positive definite (singular mass matrix?)");
        return COMPLY_ERROR;
      }
      damping = applyRatios(critical, command.damping_ratio, task_rotation);
    } else {
      damping = blockDiagonal(command.damping_translational, command.damping_rotational,
                              task_rotation, rotated);
    }

    const Vector6d wrench = -stiffness * pose_error - damping * twist_error +
                            Vector6d(Eigen::Map<const Vector6d>(command.wrench_feedforward));
    typename Joints::Vector torque = jacobian.transpose().lazyProduct(wrench);

    torque += nullspaceTorque<N>(jacobian, q, dq, command);

    for (int i = 0; i < n; ++i) {
      output.torque[i] = torque[i] + command.torque_feedforward[i];
    }
    return COMPLY_OK;
  }

  /// Nullspace: tau_0 - J^T (J J^T + lambda^2 I)^-1 J tau_0, a 6x6 solve instead of an SVD.
  template <int N>
  typename Sized<N>::Vector nullspaceTorque(
      const typename Sized<N>::Jacobian& jacobian, const typename Sized<N>::Vector& q,
      const typename Sized<N>::Vector& dq, const comply_cartesian_command& command) const noexcept {
    const int n = dof_;
    typename Sized<N>::Vector nullspace_torque(n);
    for (int i = 0; i < n; ++i) {
      nullspace_torque[i] =
          command.nullspace_stiffness[i] * (command.nullspace_position[i] - q[i]) -
          command.nullspace_damping[i] * dq[i];
    }
    // lazyProduct: a plain coefficient loop; the general matrix product kernel that a
    // dynamic-width operand would select is several times slower at this size.
    const Matrix6d regularised = jacobian.lazyProduct(jacobian.transpose()) +
                                 nullspace_damping_ * nullspace_damping_ * Matrix6d::Identity();
    const Vector6d projected = jacobian.lazyProduct(nullspace_torque);
    Vector6d task_part;
    if (!solvePositiveDefinite(regularised, projected, task_part)) {
      // Only without regularisation at a singular Jacobian: LDLT still gives a least-squares
      // answer where a Cholesky factorisation stops.
      task_part = Eigen::LDLT<Matrix6d>(regularised).solve(projected);
    }
    return nullspace_torque - jacobian.transpose().lazyProduct(task_part);
  }

  // Keeps the eigenbasis of the last cycle: the double diagonalisation then costs about one
  // Jacobi sweep instead of a full eigen solve.
  CriticalDampingTracker critical_damping_;
  Step step_ = &CartesianImpedance::stepSized<Eigen::Dynamic>;
  int dof_ = 0;
  double nullspace_damping_ = 0.05;
  double inertia_regularisation_ = 1e-6;
  bool use_mass_matrix_ = true;
  bool task_frame_in_tcp_ = false;  ///< command.task_frame relative to the measured TCP
};

}  // namespace
}  // namespace comply::controllers

COMPLY_EXPORT_CONTROLLER(comply::controllers::CartesianImpedance, "cartesian_impedance")
