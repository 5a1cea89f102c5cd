#include "comply/pipeline/wall_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace comply::pipeline {
namespace {

// Sweeps of projectInside(): one suffices for walls at right angles (a box); walls at an acute
// angle converge geometrically, and what is left after these is far below a millimetre.
constexpr int kProjectionSweeps = 16;

}  // namespace

bool compileWalls(const std::vector<WallPlane>& walls, const std::vector<WallBox>& boxes,
                  WallSet& set) {
  set = WallSet{};
  if (walls.size() + 6 * boxes.size() > static_cast<std::size_t>(kMaxWallPlanes)) {
    return false;
  }
  for (const WallPlane& wall : walls) {
    set.planes[set.count++] = wall;
  }
  for (const WallBox& box : boxes) {
    (void)appendBox(box, set);  // within kMaxWallPlanes, checked above
  }
  return true;
}

bool appendBox(const WallBox& box, WallSet& set) noexcept {
  if (set.count + 6 > static_cast<int>(set.planes.size())) {
    return false;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis);
    set.planes[set.count++] = WallPlane{box.max, unit};
    set.planes[set.count++] = WallPlane{box.min, -unit};
  }
  return true;
}

double nearestWallDistance(const WallSet& set, const Eigen::Vector3d& p) noexcept {
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < set.count; ++i) {
    nearest = std::min(nearest, -signedDistance(set.planes[i], p));
  }
  return nearest;
}

bool projectInside(const WallSet& set, Eigen::Vector3d& p) noexcept {
  bool moved = false;
  for (int sweep = 0; sweep < kProjectionSweeps; ++sweep) {
    bool outside = false;
    for (int i = 0; i < set.count; ++i) {
      const double distance = signedDistance(set.planes[i], p);
      if (distance > 0.0) {
        p -= distance * set.planes[i].normal;
        outside = true;
      }
    }
    if (!outside) {
      break;
    }
    moved = true;
  }
  return moved;
}

bool removeOutward(const WallSet& set, const Eigen::Vector3d& p, double tolerance_m,
                   Eigen::Vector3d& v) noexcept {
  Eigen::Vector3d none = Eigen::Vector3d::Zero();  // no outward component: never changes
  return removeOutward(set, p, tolerance_m, v, none);
}

bool removeOutward(const WallSet& set, const Eigen::Vector3d& p, double tolerance_m,
                   Eigen::Vector3d& v, Eigen::Vector3d& a) noexcept {
  bool changed = false;
  for (int i = 0; i < set.count; ++i) {
    const WallPlane& plane = set.planes[i];
    const double outward_v = plane.normal.dot(v);
    const double outward_a = plane.normal.dot(a);
    if (!(outward_v > 0.0) && !(outward_a > 0.0)) {
      continue;
    }
    if (signedDistance(plane, p) < -tolerance_m) {
      continue;
    }
    if (outward_v > 0.0) {
      v -= outward_v * plane.normal;
      changed = true;
    }
    if (outward_a > 0.0) {
      a -= outward_a * plane.normal;
      changed = true;
    }
  }
  return changed;
}

Eigen::Vector3d barrierForce(const WallSet& set, const BarrierGains& gains,
                             const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                             double* nearest_m) noexcept {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < set.count; ++i) {
    const WallPlane& plane = set.planes[i];
    const double distance = signedDistance(plane, p);
    nearest = std::min(nearest, -distance);
    const double approach = plane.normal.dot(v);
    const double depth = gains.brake_distance_m + distance;
    if (!(approach > 0.0) || !(depth > 0.0)) {
      continue;
    }
    const double engaged = std::min(approach / kBarrierEngageSpeed, 1.0);
    force -= (gains.stiffness_n_per_m * depth * engaged + gains.damping_n_s_per_m * approach) *
             plane.normal;
  }
  if (nearest_m != nullptr) {
    *nearest_m = nearest;
  }
  return force;
}

}  // namespace comply::pipeline
