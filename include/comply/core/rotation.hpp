#pragma once
// Orientation error on SO(3) via the unit-quaternion logarithm. Every function is real-time safe.

#include <Eigen/Geometry>

namespace comply {

/// Rotation vector phi = 2 log(q) of a unit quaternion (axis * angle, |phi| <= pi when w >= 0).
/// q and -q are the same rotation; the sign of w selects the short way, so callers that must
/// not flip at 180 degrees take care of the hemisphere themselves (see orientationError).
Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q);

/// Rotation vector that takes `current` to `desired`, expressed in the base frame:
/// phi = R_current * 2 log(current^-1 * desired), short way round (hemisphere of w >= 0).
/// Used as e_rot = -phi in the impedance law, so a positive stiffness pulls toward `desired`.
Eigen::Vector3d orientationError(const Eigen::Quaterniond& current,
                                 const Eigen::Quaterniond& desired);

}  // namespace comply
