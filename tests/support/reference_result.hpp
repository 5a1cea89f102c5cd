#pragma once
// What a reference implementation (KDL, MuJoCo) reports for one joint state. Joint-space
// quantities follow the joint order given to the reference's constructor.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace comply::testing {

struct ReferenceResult {
  /// Tip frame origin in the base frame [m].
  Eigen::Vector3d position;
  /// Tip frame orientation in the base frame (unit quaternion).
  Eigen::Quaterniond orientation;
  /// Geometric Jacobian of the tip frame origin: rows 0-2 linear velocity, rows 3-5 angular
  /// velocity, both in base-frame axes.
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian;
  /// g(q): the torque that holds the arm against gravity (0, 0, -9.81) m/s^2 in the base frame.
  Eigen::VectorXd gravity;
  /// C(q, dq) dq [N m].
  Eigen::VectorXd coriolis;
  /// M(q).
  Eigen::MatrixXd mass_matrix;
};

/// Gravity used by every reference, in the base frame [m/s^2].
inline constexpr double kReferenceGravity = 9.81;

}  // namespace comply::testing
