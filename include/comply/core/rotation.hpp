#pragma once
// SO(3) for the whole tree: the hat map, the quaternion exponential and logarithm, the right
// Jacobian and its inverse, and the orientation error the laws use. Every function is real-time
// safe: no allocation, no exception.

#include <Eigen/Geometry>

namespace comply {

/// The hat map: skew(v) w == v x w.
Eigen::Matrix3d skew(const Eigen::Vector3d& v) noexcept;

/// Rotation vector phi = 2 log(q) of a unit quaternion (axis * angle, |phi| <= pi when w >= 0).
/// q and -q are the same rotation; the sign of w selects the short way, so callers that must
/// not flip at 180 degrees take care of the hemisphere themselves (see orientationError).
Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q) noexcept;

/// Its inverse: the unit quaternion of rotation vector `phi` (Exp(phi), w >= 0 for |phi| <= pi).
Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& phi) noexcept;

/// The right Jacobian of SO(3): the body angular velocity of Exp(phi(t)) is J_r(phi) dphi/dt.
Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& phi) noexcept;

/// Its inverse (|phi| < pi, where J_r is invertible).
Eigen::Matrix3d rightJacobianInverse(const Eigen::Vector3d& phi) noexcept;

/// Rotation vector that takes `current` to `desired`, expressed in the base frame:
/// phi = R_current * 2 log(current^-1 * desired), short way round (hemisphere of w >= 0).
/// Used as e_rot = -phi in the impedance law, so a positive stiffness pulls toward `desired`.
Eigen::Vector3d orientationError(const Eigen::Quaterniond& current,
                                 const Eigen::Quaterniond& desired) noexcept;

}  // namespace comply
