#pragma once
// Virtual walls as geometry: half-spaces of the base frame the TCP may not leave. A wall is a
// plane through `point` with outward unit `normal`; the allowed side is behind the normal,
// normal . (x - point) <= 0. An axis-aligned box (its min and max corners) is the six walls of
// its faces, normals outward, so the TCP is kept inside it. Every wall and every box applies at
// once: the allowed region is their intersection.
//
// The cycle reads a WallSet, a fixed-size list of half-spaces (no heap), and the functions below,
// none of which allocates or throws. virtual_walls.hpp is the stage that uses them.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace comply::pipeline {

/// A wall as written in the controller file (walls:), base frame [m].
struct WallPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< outward, unit
};

/// A box as written in the controller file (boxes:), axis-aligned in the base frame [m].
struct WallBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
};

/// Half-spaces of the controller file the cycle holds inline: walls plus six per box.
inline constexpr int kMaxWallPlanes = 48;
/// Besides them, the six faces of the box a command sets (the workspace group).
inline constexpr int kMaxCommandedPlanes = 6;

/// The allowed region: every plane's back side.
struct WallSet {
  std::array<WallPlane, kMaxWallPlanes + kMaxCommandedPlanes> planes{};
  int count = 0;
  [[nodiscard]] bool empty() const noexcept { return count == 0; }
};

/// The barrier's gains (wall.*).
struct BarrierGains {
  double brake_distance_m = 0.0;   ///< the barrier acts this close to a wall
  double stiffness_n_per_m = 0.0;  ///< x the depth into the braking zone
  double damping_n_s_per_m = 0.0;  ///< x the approach speed
};

/// The walls and boxes as one set of half-spaces; false when they are more than kMaxWallPlanes.
bool compileWalls(const std::vector<WallPlane>& walls, const std::vector<WallBox>& boxes,
                  WallSet& set);

/// Appends the six faces of `box` to `set`; false (and `set` unchanged) without room for them.
bool appendBox(const WallBox& box, WallSet& set) noexcept;

/// normal . (p - point): > 0 past the wall, its magnitude the distance [m].
[[nodiscard]] inline double signedDistance(const WallPlane& plane,
                                           const Eigen::Vector3d& p) noexcept {
  return plane.normal.dot(p - plane.point);
}

/// The distance from `p` to the nearest wall [m]: negative when `p` is past one (by the deepest
/// penetration); +infinity without walls.
[[nodiscard]] double nearestWallDistance(const WallSet& set, const Eigen::Vector3d& p) noexcept;

/// Moves `p` onto the allowed region when it is outside (projections onto each violated plane in
/// turn, exact for one wall, a box, or walls at right angles; a few sweeps otherwise). True when
/// `p` moved.
bool projectInside(const WallSet& set, Eigen::Vector3d& p) noexcept;

/// Takes from `v` its component out through every wall `p` lies on or past (within `tolerance_m`)
/// : a reference velocity or acceleration that would carry `p` through a wall. True when `v`
/// changed.
bool removeOutward(const WallSet& set, const Eigen::Vector3d& p, double tolerance_m,
                   Eigen::Vector3d& v) noexcept;
/// The same for two vectors at one point (a reference's velocity and acceleration), each wall's
/// distance computed once. True when either changed.
bool removeOutward(const WallSet& set, const Eigen::Vector3d& p, double tolerance_m,
                   Eigen::Vector3d& v, Eigen::Vector3d& a) noexcept;

/// The speed [m/s] at which the barrier's spring is fully engaged: below it the spring fades to
/// zero with the approach speed, so the force is continuous as the TCP stops, and zero when it
/// moves away (the barrier only ever takes energy out).
inline constexpr double kBarrierEngageSpeed = 0.02;

/// The barrier force on a TCP at `p` moving at `v` [N, base frame]: for each wall `p` is within
/// brake_distance of (or past) while moving toward it at approach speed u = normal . v > 0,
///   F = -normal ( k e min(u / kBarrierEngageSpeed, 1) + c u ),  e = brake_distance + distance
/// e the depth into the braking zone. F . v <= 0 always: the barrier is passive.
/// With `nearest_m`, also nearestWallDistance(set, p) into it, from the same distances.
[[nodiscard]] Eigen::Vector3d barrierForce(const WallSet& set, const BarrierGains& gains,
                                           const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                                           double* nearest_m = nullptr) noexcept;

}  // namespace comply::pipeline
