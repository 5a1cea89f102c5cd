// Nullspace projection of the Cartesian law on the FR3 at home. With every task gain zero the
// plugin's torque is the projected nullspace torque N^T tau_0 alone, tau_0 = K_ns (q_ns - q) -
// D_ns dq. The reference projector is built here from an SVD of J, a different route from the
// plugin's 6x6 solve: J^+ = V diag(s / (s^2 + lambda^2)) U^T, N^T = I - J^T (J^+)^T.

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <vector>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kRelativeTolerance = 1e-9;

Eigen::MatrixXd nullspaceProjectorTransposed(const Matrix6Xd& jacobian, double lambda) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  const Eigen::VectorXd damped_inverse =
      s.cwiseQuotient((s.array().square() + lambda * lambda).matrix());
  const Eigen::MatrixXd pseudo_inverse =
      svd.matrixV() * damped_inverse.asDiagonal() * svd.matrixU().transpose();
  const auto n = jacobian.cols();
  return Eigen::MatrixXd::Identity(n, n) - jacobian.transpose() * pseudo_inverse.transpose();
}

class CartesianNullspace : public ::testing::Test {
 protected:
  Fr3 fr3_;
  comply_input input_ = fr3_.inputAtHome({0.2, -0.1, 0.3, 0.15, -0.25, 0.1, 0.4});
  comply_cartesian_command command_ = nullspaceOnlyCommand();
  Eigen::VectorXd nullspace_torque_ = unprojectedNullspaceTorque();

  [[nodiscard]] comply_cartesian_command nullspaceOnlyCommand() const {
    comply_cartesian_command command = holdCommand(input_);
    // Task gains zero but a pose offset present: it must not leak into the torque.
    command.position[0] += 0.05;
    const double offsets[7] = {0.3, -0.2, 0.25, 0.1, -0.35, 0.2, -0.15};
    const double stiffness[7] = {40.0, 30.0, 35.0, 25.0, 10.0, 8.0, 5.0};
    for (int i = 0; i < 7; ++i) {
      command.nullspace_position[i] = input_.position[i] + offsets[i];
      command.nullspace_stiffness[i] = stiffness[i];
      command.nullspace_damping[i] = 2.0;
    }
    return command;
  }

  [[nodiscard]] Eigen::VectorXd unprojectedNullspaceTorque() const {
    Eigen::VectorXd torque(7);
    for (int i = 0; i < 7; ++i) {
      torque[i] =
          command_.nullspace_stiffness[i] * (command_.nullspace_position[i] - input_.position[i]) -
          command_.nullspace_damping[i] * input_.velocity[i];
    }
    return torque;
  }

  /// |J tau| relative to |J| |tau_0|: how much task-space force the torque produces.
  [[nodiscard]] double taskLeakage(const Eigen::VectorXd& torque) const {
    const Matrix6Xd jacobian = jacobianOf(input_);
    return (jacobian * torque).norm() / (jacobian.norm() * nullspace_torque_.norm());
  }
};

TEST_F(CartesianNullspace, UndampedProjectionProducesNoTaskForce) {
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7,
                             numberParameter("nullspace_dls_damping", 0.0));
  const Eigen::VectorXd torque = stepTorque(law, input_, &command_);

  EXPECT_LT(taskLeakage(torque), kRelativeTolerance);
  const Eigen::VectorXd expected =
      nullspaceProjectorTransposed(jacobianOf(input_), 0.0) * nullspace_torque_;
  EXPECT_LT(relativeError(torque, expected), kRelativeTolerance);
  // The projection removes something but leaves a usable posture torque.
  EXPECT_GT(torque.norm(), 0.1 * nullspace_torque_.norm());
  EXPECT_GT((torque - nullspace_torque_).norm(), 0.1 * nullspace_torque_.norm());
}

TEST_F(CartesianNullspace, DefaultDampingLeaksALittleAsDerived) {
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7, {});  // lambda = 0.05
  const Eigen::VectorXd torque = stepTorque(law, input_, &command_);

  const double lambda = 0.05;
  const Eigen::VectorXd expected =
      nullspaceProjectorTransposed(jacobianOf(input_), lambda) * nullspace_torque_;
  EXPECT_LT(relativeError(torque, expected), kRelativeTolerance);
  // J N^T tau_0 = lambda^2 (J J^T + lambda^2 I)^-1 J tau_0: small, yet clearly not rounding.
  const double leakage = taskLeakage(torque);
  EXPECT_GT(leakage, 1e-6);
  EXPECT_LT(leakage, 0.05);
}

TEST_F(CartesianNullspace, DampingParameterChangesTheProjection) {
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7,
                             numberParameter("nullspace_dls_damping", 0.3));
  const Eigen::VectorXd torque = stepTorque(law, input_, &command_);
  const Eigen::VectorXd expected =
      nullspaceProjectorTransposed(jacobianOf(input_), 0.3) * nullspace_torque_;
  EXPECT_LT(relativeError(torque, expected), kRelativeTolerance);
  const Eigen::VectorXd default_damping =
      nullspaceProjectorTransposed(jacobianOf(input_), 0.05) * nullspace_torque_;
  EXPECT_GT((torque - default_damping).norm(), 1e-6 * torque.norm());
}

}  // namespace
}  // namespace comply::law_test
