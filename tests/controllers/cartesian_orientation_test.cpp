// Orientation error of the Cartesian law on the FR3 at home. A reference turned by angle a about
// base z (R_d = R_z(a) R) has the rotation vector a z exactly, at any angle below pi, so the
// torque must be J^T [0; 0; 0; 0; 0; k a] with a moment that turns the TCP toward the reference.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kRotationalStiffness = 40.0;  // N m/rad
constexpr double kRelativeTolerance = 1e-9;

class CartesianOrientation : public CartesianLawAtHome {
 protected:
  /// Reference orientation turned by `angle` about base z; translation held stiffly in place.
  [[nodiscard]] comply_cartesian_command turnedAboutBaseZ(double angle) const {
    comply_cartesian_command command = holdCommand(input_);
    const Eigen::Quaterniond desired =
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())) *
        tcpOrientationOf(input_);
    writeXyzw(desired, command.orientation);
    writeRowMajor(kRotationalStiffness * Eigen::Matrix3d::Identity(), command.stiffness_rotational);
    writeRowMajor(800.0 * Eigen::Matrix3d::Identity(), command.stiffness_translational);
    return command;
  }

  [[nodiscard]] Eigen::VectorXd expectedTorque(double angle) const {
    Vector6d wrench = Vector6d::Zero();
    wrench[5] = kRotationalStiffness * angle;
    return jacobianOf(input_).transpose() * wrench;
  }
};

TEST_F(CartesianOrientation, SmallTurnAboutBaseZ) {
  for (const double angle : {0.01, -0.01, 1e-6}) {
    const comply_cartesian_command command = turnedAboutBaseZ(angle);
    const Eigen::VectorXd torque = stepTorque(law_, input_, &command);
    EXPECT_LT(relativeError(torque, expectedTorque(angle)), kRelativeTolerance)
        << "angle " << angle;
    // Restoring: the recovered moment about z has the sign of the reference's offset.
    const Vector6d wrench = wrenchFromTorque(jacobianOf(input_), torque);
    EXPECT_GT(wrench[5] * angle, 0.0) << "angle " << angle;
  }
}

TEST_F(CartesianOrientation, LargeTurnUsesTheLogarithmNotASmallAngleApproximation) {
  // At 2 rad, sin(a) or 2 sin(a/2) would differ from a by more than 10 %.
  const double angle = 2.0;
  const comply_cartesian_command command = turnedAboutBaseZ(angle);
  EXPECT_LT(relativeError(stepTorque(law_, input_, &command), expectedTorque(angle)),
            kRelativeTolerance);
}

TEST_F(CartesianOrientation, NegatedReferenceQuaternionIsTheSameOrientation) {
  const double angle = 0.3;
  comply_cartesian_command command = turnedAboutBaseZ(angle);
  for (int k = 0; k < 4; ++k) {
    command.orientation[k] = -command.orientation[k];
  }
  ASSERT_LT(command.orientation[3], 0.0);
  EXPECT_LT(relativeError(stepTorque(law_, input_, &command), expectedTorque(angle)),
            kRelativeTolerance);
}

TEST_F(CartesianOrientation, RotationalStiffnessTurnsWithTheTaskFrame) {
  // Stiffness diag(0, 0, k) about the task z, with the task frame's z on base x: a turn about
  // base z meets no stiffness, a turn about base x meets k.
  const Eigen::Quaterniond z_onto_x(
      Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitY()));  // maps z to x
  const double angle = 0.02;
  comply_cartesian_command about_z = turnedAboutBaseZ(angle);
  writeRowMajor(Eigen::Vector3d(0.0, 0.0, kRotationalStiffness).asDiagonal().toDenseMatrix(),
                about_z.stiffness_rotational);
  writeXyzw(z_onto_x, about_z.task_frame);
  const Eigen::VectorXd torque_z = stepTorque(law_, input_, &about_z);
  EXPECT_LT(torque_z.norm(), 1e-12 * expectedTorque(angle).norm());

  comply_cartesian_command about_x = about_z;
  writeXyzw(Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())) *
                tcpOrientationOf(input_),
            about_x.orientation);
  Vector6d wrench = Vector6d::Zero();
  wrench[3] = kRotationalStiffness * angle;
  const Eigen::VectorXd expected = jacobianOf(input_).transpose() * wrench;
  EXPECT_LT(relativeError(stepTorque(law_, input_, &about_x), expected), kRelativeTolerance);
}

}  // namespace
}  // namespace comply::law_test
