// Stiffness is commanded in a task frame: on the FR3 at home, a stiffness of diag(1000, 1000, 50)
// N/m in a frame turned by 30 degrees must be soft along the turned z axis and stiff across it.
// The force is read back from the torque by least squares over J^T, which is exact here because
// the nullspace gains are zero (the torque lies in the range of J^T).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kStiff = 1000.0;
constexpr double kCompliant = 50.0;
constexpr double kDisplacement = 0.01;  // m
constexpr double kRelativeTolerance = 1e-9;

class CartesianTaskFrame : public CartesianLawAtHome {
 protected:
  Eigen::Matrix3d task_rotation_ =
      Eigen::AngleAxisd(std::numbers::pi / 6.0, Eigen::Vector3d(1.0, 2.0, -0.5).normalized())
          .toRotationMatrix();

  /// Reference moved by kDisplacement along `direction` (base frame), gains in `task_rotation`.
  [[nodiscard]] comply_cartesian_command displaced(const Eigen::Vector3d& direction,
                                                   const Eigen::Matrix3d& task_rotation) const {
    comply_cartesian_command command = holdCommand(input_);
    for (int row = 0; row < 3; ++row) {
      command.position[row] += kDisplacement * direction[row];
    }
    writeRowMajor(Eigen::Vector3d(kStiff, kStiff, kCompliant).asDiagonal().toDenseMatrix(),
                  command.stiffness_translational);
    writeRowMajor(300.0 * Eigen::Matrix3d::Identity(), command.stiffness_rotational);
    writeXyzw(Eigen::Quaterniond(task_rotation), command.task_frame);
    return command;
  }

  [[nodiscard]] Vector6d wrenchFor(const comply_cartesian_command& command) {
    return wrenchFromTorque(jacobianOf(input_), stepTorque(law_, input_, &command));
  }
};

TEST_F(CartesianTaskFrame, CompliantAxisFollowsTheTaskFrame) {
  const Eigen::Vector3d axis = task_rotation_ * Eigen::Vector3d::UnitZ();
  const Vector6d wrench = wrenchFor(displaced(axis, task_rotation_));
  Vector6d expected = Vector6d::Zero();
  expected.head<3>() = kCompliant * kDisplacement * axis;  // toward the reference
  EXPECT_LT(relativeError(wrench, expected), kRelativeTolerance) << wrench.transpose();
}

TEST_F(CartesianTaskFrame, StiffAxesFollowTheTaskFrame) {
  const std::array<Eigen::Vector3d, 2> stiff_task_axes = {Eigen::Vector3d::UnitX(),
                                                          Eigen::Vector3d::UnitY()};
  for (const Eigen::Vector3d& task_axis : stiff_task_axes) {
    const Eigen::Vector3d axis = task_rotation_ * task_axis;
    const Vector6d wrench = wrenchFor(displaced(axis, task_rotation_));
    Vector6d expected = Vector6d::Zero();
    expected.head<3>() = kStiff * kDisplacement * axis;
    EXPECT_LT(relativeError(wrench, expected), kRelativeTolerance) << wrench.transpose();
  }
}

TEST_F(CartesianTaskFrame, TorqueMatchesJacobianTransposeOfRotatedStiffness) {
  // A displacement along no particular axis, compared in joint space rather than wrench space.
  const Eigen::Vector3d direction = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const comply_cartesian_command command = displaced(direction, task_rotation_);
  const Eigen::Matrix3d base_stiffness = task_rotation_ *
                                         Eigen::Vector3d(kStiff, kStiff, kCompliant).asDiagonal() *
                                         task_rotation_.transpose();
  Vector6d pose_error = Vector6d::Zero();
  pose_error.head<3>() = -kDisplacement * direction;  // p - p_d
  Vector6d spring_wrench = Vector6d::Zero();
  spring_wrench.head<3>() = -base_stiffness * pose_error.head<3>();
  const Eigen::VectorXd expected = jacobianOf(input_).transpose() * spring_wrench;

  EXPECT_LT(relativeError(stepTorque(law_, input_, &command), expected), kRelativeTolerance);
}

TEST_F(CartesianTaskFrame, IdentityTaskFrameGivesADifferentTorque) {
  const Eigen::Vector3d axis = task_rotation_ * Eigen::Vector3d::UnitZ();
  const comply_cartesian_command rotated_command = displaced(axis, task_rotation_);
  const Eigen::VectorXd rotated = stepTorque(law_, input_, &rotated_command);
  const comply_cartesian_command unrotated_command = displaced(axis, Eigen::Matrix3d::Identity());
  const Eigen::VectorXd unrotated = stepTorque(law_, input_, &unrotated_command);

  // Same displacement, base-aligned gains: the force is diag(1000, 1000, 50) d, not 50 d.
  Vector6d expected = Vector6d::Zero();
  expected.head<3>() =
      Eigen::Vector3d(kStiff, kStiff, kCompliant).asDiagonal() * (kDisplacement * axis);
  EXPECT_LT(relativeError(wrenchFromTorque(jacobianOf(input_), unrotated), expected),
            kRelativeTolerance);
  EXPECT_GT((rotated - unrotated).norm(), 0.5 * rotated.norm());
}

TEST_F(CartesianTaskFrame, TaskFrameQuaternionIsNormalised) {
  // A sender's quaternion that is off unit length by rounding or scaling is the same frame.
  const Eigen::Vector3d axis = task_rotation_ * Eigen::Vector3d::UnitZ();
  comply_cartesian_command unit = displaced(axis, task_rotation_);
  comply_cartesian_command scaled = unit;
  for (double& component : scaled.task_frame) {
    component *= 3.0;
  }
  const Eigen::VectorXd expected = stepTorque(law_, input_, &unit);
  EXPECT_LT(relativeError(stepTorque(law_, input_, &scaled), expected), kRelativeTolerance);
}

TEST_F(CartesianTaskFrame, TaskFrameRelativeToTheMeasuredTcpTurnsWithTheTool) {
  // Same command, gains relative to the TCP: the compliant axis is R_tcp R_task e_z, and it
  // moves when only the measured orientation does.
  plugin::ParameterMap parameters;
  parameters["task_frame_reference"].text = "tcp";
  parameters["task_frame_reference"].is_text = true;
  plugin::PluginInstance tool_law(cartesianImpedanceLibrary(), fr3_.model.dof(), parameters);
  const Eigen::Matrix3d tcp_rotation =
      Eigen::Quaterniond(input_.tcp_orientation[3], input_.tcp_orientation[0],
                         input_.tcp_orientation[1], input_.tcp_orientation[2])
          .toRotationMatrix();
  const Eigen::Vector3d axis = tcp_rotation * task_rotation_ * Eigen::Vector3d::UnitZ();
  const comply_cartesian_command command = displaced(axis, task_rotation_);
  const Vector6d wrench =
      wrenchFromTorque(jacobianOf(input_), stepTorque(tool_law, input_, &command));
  Vector6d expected = Vector6d::Zero();
  expected.head<3>() = kCompliant * kDisplacement * axis;
  EXPECT_LT(relativeError(wrench, expected), kRelativeTolerance) << wrench.transpose();
  // The base-frame law reads the same command differently unless the TCP is base-aligned.
  ASSERT_GT((tcp_rotation - Eigen::Matrix3d::Identity()).norm(), 0.1);
  EXPECT_GT(relativeError(wrenchFor(command), expected), 0.1);
}

TEST_F(CartesianTaskFrame, UnknownTaskFrameReferenceIsRefusedAtCreation) {
  plugin::ParameterMap parameters;
  parameters["task_frame_reference"].text = "flange";
  parameters["task_frame_reference"].is_text = true;
  try {
    plugin::PluginInstance law(cartesianImpedanceLibrary(), fr3_.model.dof(), parameters);
    FAIL() << "created with task_frame_reference: flange";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("task_frame_reference must be base or tcp"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace comply::law_test
