#include "comply/task/frames.hpp"

#include <cmath>

namespace comply::task {
namespace {

constexpr double kTiny = 1e-12;

/// `vector` minus its component along unit `axis`, normalised; nullopt when nothing is left.
std::optional<Eigen::Vector3d> orthogonalPart(const Eigen::Vector3d& vector,
                                              const Eigen::Vector3d& axis) {
  const Eigen::Vector3d part = vector - vector.dot(axis) * axis;
  const double norm = part.norm();
  if (norm < 1e-9 * std::max(1.0, vector.norm())) {
    return std::nullopt;
  }
  return part / norm;
}

}  // namespace

std::optional<Eigen::Matrix3d> frenetFrame(const Eigen::Vector3d& velocity,
                                           const Eigen::Vector3d& acceleration,
                                           const std::optional<Eigen::Vector3d>& previous_normal,
                                           const Eigen::Vector3d& fallback_normal,
                                           double min_curvature_per_m) {
  const double speed = velocity.norm();
  if (speed < kTiny) {
    return std::nullopt;
  }
  const Eigen::Vector3d tangent = velocity / speed;
  const double curvature = velocity.cross(acceleration).norm() / (speed * speed * speed);

  std::optional<Eigen::Vector3d> normal;
  if (curvature >= min_curvature_per_m) {
    // The part of r'' orthogonal to r' points towards the centre of curvature.
    normal = orthogonalPart(acceleration, tangent);
  }
  if (!normal && previous_normal) {
    normal = orthogonalPart(*previous_normal, tangent);
  }
  if (!normal) {
    normal = orthogonalPart(fallback_normal, tangent);
  }
  if (!normal) {
    // The fallback is parallel to the tangent: any orthogonal direction will do.
    normal = orthogonalPart(Eigen::Vector3d::UnitX(), tangent);
    if (!normal) {
      normal = orthogonalPart(Eigen::Vector3d::UnitY(), tangent);
    }
  }
  if (previous_normal && normal->dot(*previous_normal) < 0.0) {
    *normal = -*normal;  // continuity through an inflection
  }
  Eigen::Matrix3d frame;
  frame.col(0) = tangent;
  frame.col(1) = *normal;
  frame.col(2) = tangent.cross(*normal);
  return frame;
}

std::optional<Eigen::Matrix3d> darbouxFrame(const Eigen::Vector3d& tangent,
                                            const Eigen::Vector3d& surface_normal) {
  const double length = tangent.norm();
  if (length < kTiny) {
    return std::nullopt;
  }
  const Eigen::Vector3d unit_tangent = tangent / length;
  const std::optional<Eigen::Vector3d> normal = orthogonalPart(surface_normal, unit_tangent);
  if (!normal) {
    return std::nullopt;
  }
  Eigen::Matrix3d frame;
  frame.col(0) = unit_tangent;
  frame.col(1) = *normal;
  frame.col(2) = unit_tangent.cross(*normal);
  return frame;
}

}  // namespace comply::task
