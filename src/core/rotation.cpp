#include "comply/core/rotation.hpp"

#include <cmath>

namespace comply {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) noexcept {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q) noexcept {
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

Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& phi) noexcept {
  const double angle = phi.norm();
  if (angle < 1e-12) {
    // No axis to divide by: the first-order quaternion, which keeps the derivative at zero.
    return Eigen::Quaterniond(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

// Below 1e-6 rad the closed forms lose their digits to cancellation (1 - cos, angle - sin); the
// series to second order in phi is off there by at most angle^2 / 12 relative, below 1e-13.

Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& phi) noexcept {
  const double angle = phi.norm();
  const Eigen::Matrix3d phi_hat = skew(phi);
  if (angle < 1e-6) {
    return Eigen::Matrix3d::Identity() - 0.5 * phi_hat + phi_hat * phi_hat / 6.0;
  }
  const double a2 = angle * angle;
  return Eigen::Matrix3d::Identity() - (1 - std::cos(angle)) / a2 * phi_hat +
         (angle - std::sin(angle)) / (a2 * angle) * phi_hat * phi_hat;
}

Eigen::Matrix3d rightJacobianInverse(const Eigen::Vector3d& phi) noexcept {
  const double angle = phi.norm();
  const Eigen::Matrix3d phi_hat = skew(phi);
  if (angle < 1e-6) {
    return Eigen::Matrix3d::Identity() + 0.5 * phi_hat + phi_hat * phi_hat / 12.0;
  }
  const double a2 = angle * angle;
  const double k = 1.0 / a2 - (1 + std::cos(angle)) / (2 * angle * std::sin(angle));
  return Eigen::Matrix3d::Identity() + 0.5 * phi_hat + k * phi_hat * phi_hat;
}

Eigen::Vector3d orientationError(const Eigen::Quaterniond& current,
                                 const Eigen::Quaterniond& desired) noexcept {
  Eigen::Quaterniond relative = current.conjugate() * desired;
  if (relative.w() < 0.0) {
    relative.coeffs() = -relative.coeffs();
  }
  return current.toRotationMatrix() * quaternionLog(relative);
}

}  // namespace comply
