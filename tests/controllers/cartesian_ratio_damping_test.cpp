// Ratio-mode damping of the Cartesian law on the FR3: D = S D_crit S, with D_crit the critical
// damping of K on the Cartesian inertia Lambda = (J M^-1 J^T + reg I)^-1. The reference here
// inverts with dense inverses and solves the generalised problem K v = w^2 Lambda v (V^T Lambda V
// = I), giving D_crit = Lambda V diag(2 w) V^T Lambda; the plugin instead factors Lambda^-1 and
// runs a warm-started Jacobi solver, so agreement checks both against each other.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <numbers>
#include <vector>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kInertiaRegularisation = 1e-6;  // the plugin's default
constexpr double kRelativeTolerance = 1e-9;

Matrix6d cartesianInertia(const comply_input& input) {
  const Matrix6Xd jacobian = jacobianOf(input);
  const Eigen::MatrixXd mass_inverse = massMatrixOf(input).inverse();
  const Matrix6d inverse_inertia = jacobian * mass_inverse * jacobian.transpose() +
                                   kInertiaRegularisation * Matrix6d::Identity();
  return inverse_inertia.inverse();
}

Matrix6d criticalDampingReference(const Matrix6d& stiffness, const Matrix6d& inertia) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> eigen(stiffness, inertia);
  const Vector6d frequency = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Matrix6d modes = inertia * eigen.eigenvectors();
  return modes * (2.0 * frequency).asDiagonal() * modes.transpose();
}

Matrix6d blockDiagonal(const Eigen::Matrix3d& top, const Eigen::Matrix3d& bottom) {
  Matrix6d result = Matrix6d::Zero();
  result.topLeftCorner<3, 3>() = top;
  result.bottomRightCorner<3, 3>() = bottom;
  return result;
}

class CartesianRatioDamping : public ::testing::Test {
 protected:
  Fr3 fr3_;
  plugin::PluginInstance law_{cartesianImpedanceLibrary(), fr3_.model.dof(), {}};
  Eigen::Matrix3d task_rotation_ =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, -1.0, 0.6).normalized()).toRotationMatrix();
  Eigen::Matrix3d translational_stiffness_ = Eigen::Vector3d(800.0, 600.0, 150.0).asDiagonal();
  Eigen::Matrix3d rotational_stiffness_ = Eigen::Vector3d(40.0, 30.0, 10.0).asDiagonal();

  /// Zero pose error, stiffness in the rotated task frame, damping given as ratios.
  [[nodiscard]] comply_cartesian_command ratioCommand(const comply_input& input,
                                                      const Vector6d& ratio) const {
    comply_cartesian_command command = holdCommand(input);
    writeRowMajor(translational_stiffness_, command.stiffness_translational);
    writeRowMajor(rotational_stiffness_, command.stiffness_rotational);
    writeXyzw(Eigen::Quaterniond(task_rotation_), command.task_frame);
    command.damping_mode = COMPLY_DAMPING_RATIO;
    for (int k = 0; k < 6; ++k) {
      command.damping_ratio[k] = ratio[k];
    }
    // Absolute damping blocks are ignored in ratio mode; make them loud if they were not.
    writeRowMajor(1e4 * Eigen::Matrix3d::Identity(), command.damping_translational);
    writeRowMajor(1e4 * Eigen::Matrix3d::Identity(), command.damping_rotational);
    return command;
  }

  [[nodiscard]] Matrix6d baseStiffness() const {
    return blockDiagonal(task_rotation_ * translational_stiffness_ * task_rotation_.transpose(),
                         task_rotation_ * rotational_stiffness_ * task_rotation_.transpose());
  }

  [[nodiscard]] Matrix6d expectedDamping(const comply_input& input, const Vector6d& ratio) const {
    const Matrix6d critical = criticalDampingReference(baseStiffness(), cartesianInertia(input));
    const Eigen::Matrix3d r = task_rotation_;
    const Matrix6d ratio_root =
        blockDiagonal(r * ratio.head<3>().cwiseSqrt().asDiagonal() * r.transpose(),
                      r * ratio.tail<3>().cwiseSqrt().asDiagonal() * r.transpose());
    return ratio_root * critical * ratio_root;
  }

  [[nodiscard]] static Eigen::VectorXd dampingTorque(const comply_input& input,
                                                     const Matrix6d& damping) {
    const Matrix6Xd jacobian = jacobianOf(input);
    const Eigen::VectorXd dq = Eigen::Map<const Eigen::VectorXd>(input.velocity, input.dof);
    return -jacobian.transpose() * (damping * (jacobian * dq));
  }
};

const std::vector<double> kJointVelocity = {0.3, -0.2, 0.25, 0.4, -0.5, 0.35, -0.6};

TEST_F(CartesianRatioDamping, CriticalRatioMatchesGeneralisedEigenReference) {
  const comply_input input = fr3_.inputAtHome(kJointVelocity);
  const Vector6d ratio = Vector6d::Ones();
  const comply_cartesian_command command = ratioCommand(input, ratio);

  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  const Eigen::VectorXd expected = dampingTorque(input, expectedDamping(input, ratio));
  EXPECT_LT(relativeError(torque, expected), kRelativeTolerance);
  EXPECT_GT(expected.norm(), 1.0);  // a real damping torque, not a vanishing one
}

TEST_F(CartesianRatioDamping, PerAxisRatiosApplyInTheTaskFrame) {
  const comply_input input = fr3_.inputAtHome(kJointVelocity);
  Vector6d ratio;
  ratio << 0.5, 1.0, 2.0, 0.7, 1.0, 1.5;
  const comply_cartesian_command command = ratioCommand(input, ratio);

  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_LT(relativeError(torque, dampingTorque(input, expectedDamping(input, ratio))),
            kRelativeTolerance);
  // Ratios matter: the critical torque is measurably different.
  const Eigen::VectorXd critical = dampingTorque(input, expectedDamping(input, Vector6d::Ones()));
  EXPECT_GT((torque - critical).norm(), 0.01 * critical.norm());
}

TEST_F(CartesianRatioDamping, RecoveredMatrixIsCriticalOnTheCartesianInertia) {
  // With dq = 0 and target twist -e_i, the twist error is e_i and tau = -J^T D e_i: six steps
  // give D column by column. Critical damping is the symmetric positive solution of
  // D Lambda^-1 D = 4 K, checked without any eigen decomposition.
  const comply_input input = fr3_.inputAtHome();
  const Matrix6Xd jacobian = jacobianOf(input);
  Matrix6d damping;
  for (int axis = 0; axis < 6; ++axis) {
    comply_cartesian_command command = ratioCommand(input, Vector6d::Ones());
    command.twist[axis] = -1.0;
    damping.col(axis) = -wrenchFromTorque(jacobian, stepTorque(law_, input, &command));
  }
  const Matrix6d inertia = cartesianInertia(input);
  EXPECT_LT((damping - damping.transpose()).norm(), kRelativeTolerance * damping.norm());
  const Matrix6d four_k = 4.0 * baseStiffness();
  EXPECT_LT((damping * inertia.inverse() * damping - four_k).norm(),
            kRelativeTolerance * four_k.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(damping).eigenvalues().minCoeff(), 0.0);
}

TEST_F(CartesianRatioDamping, WarmStartedSolveFollowsAChangingPose) {
  // The plugin keeps its eigenbasis between cycles; a second, different pose must not inherit
  // anything from the first but the starting guess.
  const comply_input home = fr3_.inputAtHome(kJointVelocity);
  const comply_cartesian_command home_command = ratioCommand(home, Vector6d::Ones());
  (void)stepTorque(law_, home, &home_command);

  std::vector<double> moved = fr3_.robot.home;
  const double offsets[7] = {0.4, 0.3, -0.5, 0.35, 0.6, -0.4, 0.9};
  for (std::size_t i = 0; i < moved.size(); ++i) {
    moved[i] += offsets[i];
  }
  const comply_input input = inputFromModel(fr3_.model, moved, kJointVelocity);
  const comply_cartesian_command command = ratioCommand(input, Vector6d::Ones());
  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_LT(relativeError(torque, dampingTorque(input, expectedDamping(input, Vector6d::Ones()))),
            kRelativeTolerance);
}

}  // namespace
}  // namespace comply::law_test
