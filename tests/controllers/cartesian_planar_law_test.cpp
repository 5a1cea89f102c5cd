// Cartesian impedance on the planar two-link arm of test_urdfs::planarTwoLink(), with the input
// written entirely by hand from the link lengths (no model involved), so the expected torques
// follow from the law on paper:
//
//   p = (l1 c1 + l2 c12, 0, -(l1 s1 + l2 s12))    both joints rotate about +y, links along +x at 0
//   J = [ -(l1 s1 + l2 s12)   -l2 s12 ]   linear x
//       [        0               0    ]   linear y
//       [ -(l1 c1 + l2 c12)   -l2 c12 ]   linear z
//       [ 0 0 ]  [ 1 1 ]  [ 0 0 ]         angular x, y, z
//
// Nullspace gains stay zero, so the nullspace term vanishes whatever its damping.

#include <gtest/gtest.h>

#include <cmath>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kLink1 = 1.0;
constexpr double kLink2 = 0.8;
constexpr double kTolerance = 1e-12;

/// The planar arm's state and its hand-derived kinematics.
struct PlanarArm {
  double q1;
  double q2;
  double dq1 = 0.0;
  double dq2 = 0.0;

  [[nodiscard]] double x() const { return kLink1 * std::cos(q1) + kLink2 * std::cos(q1 + q2); }
  [[nodiscard]] double z() const { return -(kLink1 * std::sin(q1) + kLink2 * std::sin(q1 + q2)); }
  // d(x, z)/dq_j: the linear Jacobian entries; the angular ones are 1 about y for both joints.
  [[nodiscard]] double dxdq1() const { return z(); }
  [[nodiscard]] double dzdq1() const { return -x(); }
  [[nodiscard]] double dxdq2() const { return -kLink2 * std::sin(q1 + q2); }
  [[nodiscard]] double dzdq2() const { return -kLink2 * std::cos(q1 + q2); }

  [[nodiscard]] comply_input input() const {
    comply_input input{};
    input.dof = 2;
    input.available = COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN;
    input.period_s = 0.001;
    writeJoints({q1, q2}, input.position);
    writeJoints({dq1, dq2}, input.velocity);
    input.tcp_position[0] = x();
    input.tcp_position[1] = 0.0;
    input.tcp_position[2] = z();
    // R_y(q1 + q2) as x, y, z, w.
    input.tcp_orientation[1] = std::sin(0.5 * (q1 + q2));
    input.tcp_orientation[3] = std::cos(0.5 * (q1 + q2));
    // Column-major, leading dimension 6: column j holds d(x, y, z, wx, wy, wz)/dq_j.
    const double columns[2][6] = {{dxdq1(), 0.0, dzdq1(), 0.0, 1.0, 0.0},
                                  {dxdq2(), 0.0, dzdq2(), 0.0, 1.0, 0.0}};
    for (int col = 0; col < 2; ++col) {
      for (int row = 0; row < 6; ++row) {
        input.jacobian[col * 6 + row] = columns[col][row];
      }
    }
    return input;
  }
};

void setDiagonal(double* row_major, double a, double b, double c) {
  writeRowMajor(Eigen::Vector3d(a, b, c).asDiagonal().toDenseMatrix(), row_major);
}

class CartesianPlanarLaw : public ::testing::Test {
 protected:
  plugin::PluginInstance law_{cartesianImpedanceLibrary(), 2, {}};
};

TEST_F(CartesianPlanarLaw, TranslationalSpringWithDiagonalStiffness) {
  const PlanarArm arm{0.3, 0.6};
  const comply_input input = arm.input();
  comply_cartesian_command command = holdCommand(input);
  const double dx = 0.02;
  const double dy = 0.01;
  const double dz = -0.03;
  command.position[0] += dx;
  command.position[1] += dy;
  command.position[2] += dz;
  const double kx = 300.0;
  const double ky = 200.0;
  const double kz = 500.0;
  setDiagonal(command.stiffness_translational, kx, ky, kz);
  // Present but inert: no orientation error and the arm is at rest.
  setDiagonal(command.stiffness_rotational, 40.0, 40.0, 40.0);
  setDiagonal(command.damping_translational, 30.0, 30.0, 30.0);
  setDiagonal(command.damping_rotational, 5.0, 5.0, 5.0);

  // Force -K (p - p_d) = (kx dx, ky dy, kz dz); the y part meets a zero Jacobian row.
  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_NEAR(torque[0], arm.dxdq1() * kx * dx + arm.dzdq1() * kz * dz, kTolerance);
  EXPECT_NEAR(torque[1], arm.dxdq2() * kx * dx + arm.dzdq2() * kz * dz, kTolerance);
  EXPECT_GT(std::abs(torque[0]), 1.0);  // not a trivially zero case
}

TEST_F(CartesianPlanarLaw, GainBlocksAreReadRowMajor) {
  // Only an asymmetric block tells row-major from column-major: K_xz couples z displacement into
  // x force, while K_zx = 0 leaves the z force uncoupled.
  const PlanarArm arm{0.3, 0.6};
  const comply_input input = arm.input();
  comply_cartesian_command command = holdCommand(input);
  const double dx = 0.02;
  const double dz = -0.03;
  command.position[0] += dx;
  command.position[2] += dz;
  const double kx = 300.0;
  const double kz = 500.0;
  const double kxz = 80.0;
  const double row_major[9] = {kx, 0.0, kxz, 0.0, 200.0, 0.0, 0.0, 0.0, kz};
  for (int k = 0; k < 9; ++k) {
    command.stiffness_translational[k] = row_major[k];
  }

  const double fx = kx * dx + kxz * dz;
  const double fz = kz * dz;
  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_NEAR(torque[0], arm.dxdq1() * fx + arm.dzdq1() * fz, kTolerance);
  EXPECT_NEAR(torque[1], arm.dxdq2() * fx + arm.dzdq2() * fz, kTolerance);
}

TEST_F(CartesianPlanarLaw, DampingActsOnTwistError) {
  PlanarArm arm{-0.4, 1.1};
  arm.dq1 = 0.4;
  arm.dq2 = -0.7;
  const comply_input input = arm.input();
  comply_cartesian_command command = holdCommand(input);
  const double target_vx = 0.1;
  const double target_vz = -0.2;
  const double target_wy = 0.3;
  command.twist[0] = target_vx;
  command.twist[2] = target_vz;
  command.twist[4] = target_wy;
  const double cx = 40.0;
  const double cz = 25.0;
  const double cry = 3.0;
  setDiagonal(command.damping_translational, cx, 10.0, cz);
  setDiagonal(command.damping_rotational, 1.0, cry, 2.0);

  const double vx = arm.dxdq1() * arm.dq1 + arm.dxdq2() * arm.dq2;
  const double vz = arm.dzdq1() * arm.dq1 + arm.dzdq2() * arm.dq2;
  const double wy = arm.dq1 + arm.dq2;
  const double fx = -cx * (vx - target_vx);
  const double fz = -cz * (vz - target_vz);
  const double my = -cry * (wy - target_wy);

  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_NEAR(torque[0], arm.dxdq1() * fx + arm.dzdq1() * fz + my, kTolerance);
  EXPECT_NEAR(torque[1], arm.dxdq2() * fx + arm.dzdq2() * fz + my, kTolerance);
}

TEST_F(CartesianPlanarLaw, RotationInThePlaneIsRestored) {
  const PlanarArm arm{0.2, -0.5};
  const comply_input input = arm.input();
  comply_cartesian_command command = holdCommand(input);
  // Reference turned by b further about +y: the moment k b about y reaches both joints fully.
  const double b = 0.05;
  command.orientation[1] = std::sin(0.5 * (arm.q1 + arm.q2 + b));
  command.orientation[3] = std::cos(0.5 * (arm.q1 + arm.q2 + b));
  const double k_ry = 60.0;
  setDiagonal(command.stiffness_rotational, 10.0, k_ry, 20.0);
  setDiagonal(command.stiffness_translational, 500.0, 500.0, 500.0);

  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_NEAR(torque[0], k_ry * b, kTolerance);
  EXPECT_NEAR(torque[1], k_ry * b, kTolerance);
}

TEST_F(CartesianPlanarLaw, FeedforwardWrenchAndTorque) {
  const PlanarArm arm{0.7, 0.9};
  const comply_input input = arm.input();
  comply_cartesian_command command = holdCommand(input);
  const double wrench[6] = {3.0, -8.0, -4.0, 1.5, 0.5, -2.5};
  for (int k = 0; k < 6; ++k) {
    command.wrench_feedforward[k] = wrench[k];
  }
  writeJoints({0.25, -1.0}, command.torque_feedforward);

  // Only x, z forces and the y moment do work on this arm.
  const Eigen::VectorXd torque = stepTorque(law_, input, &command);
  EXPECT_NEAR(torque[0], arm.dxdq1() * wrench[0] + arm.dzdq1() * wrench[2] + wrench[4] + 0.25,
              kTolerance);
  EXPECT_NEAR(torque[1], arm.dxdq2() * wrench[0] + arm.dzdq2() * wrench[2] + wrench[4] - 1.0,
              kTolerance);
}

}  // namespace
}  // namespace comply::law_test
