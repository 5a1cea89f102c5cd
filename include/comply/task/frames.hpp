#pragma once
// Compliance frames from task geometry: the "external task source" side of task-aligned
// compliance. A frame is a rotation whose columns are the task axes in the base frame; sent as a
// command's `task_frame`, it makes the stiffness and damping axes follow the geometry.

#include <Eigen/Geometry>
#include <optional>

namespace comply::task {

/// Frenet-Serret frame of a curve from its derivatives at a point (any parametrisation):
/// columns tangent T = r'/|r'|, principal normal N (towards the centre of curvature) and
/// binormal B = T x N.
///
/// Where the curvature vanishes (straight pieces, inflection points) N is undefined and, at an
/// inflection, flips. To give a compliance frame that never jumps: when |r' x r''| / |r'|^3 is
/// below `min_curvature_per_m`, N is `previous_normal` made orthogonal to T (or, without one, the
/// unit vector orthogonal to T closest to `fallback_normal`, then any orthogonal vector); and N
/// keeps the sign of `previous_normal` (so through an inflection the frame turns smoothly and N
/// points away from the centre of curvature on the far side).
///
/// Returns nullopt when r' is (numerically) zero: there is no tangent.
std::optional<Eigen::Matrix3d> frenetFrame(
    const Eigen::Vector3d& velocity, const Eigen::Vector3d& acceleration,
    const std::optional<Eigen::Vector3d>& previous_normal = std::nullopt,
    const Eigen::Vector3d& fallback_normal = Eigen::Vector3d::UnitZ(),
    double min_curvature_per_m = 1e-6);

/// Darboux frame of a curve on a surface: columns tangent T, surface normal n (made orthogonal
/// to T) and T x n. Returns nullopt when the tangent is zero or parallel to the normal.
std::optional<Eigen::Matrix3d> darbouxFrame(const Eigen::Vector3d& tangent,
                                            const Eigen::Vector3d& surface_normal);

}  // namespace comply::task
