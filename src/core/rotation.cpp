#include "comply/core/rotation.hpp"

#include <cmath>

namespace comply {

Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d v = q.vec();
  const double sin_half = v.norm();
  // atan2 is accurate near 0 and pi, where acos(w) loses half the digits.
  const double half_angle = std::atan2(sin_half, q.w());
  if (sin_half < 1e-12) {
    // Small angle: log(q) ~ v / w; keeps the derivative exact instead of returning zero.
    return 2.0 * v / q.w();
  }
  return 2.0 * half_angle * v / sin_half;
}

Eigen::Vector3d orientationError(const Eigen::Quaterniond& current,
                                 const Eigen::Quaterniond& desired) {
  Eigen::Quaterniond relative = current.conjugate() * desired;
  if (relative.w() < 0.0) {
    relative.coeffs() = -relative.coeffs();
  }
  return current.toRotationMatrix() * quaternionLog(relative);
}

}  // namespace comply
