#pragma once
// Stage "walls": planes and axis-aligned boxes of the base frame the TCP does not pass
// (walls:, boxes:, wall.*; wall_geometry.hpp), and the box the command in force sets for its phase
// of the task (the workspace group, checked at the intake: workspace_intake.hpp), besides them.
// Cartesian laws only; off, and one branch, when there are none.
//
// Two parts, so that neither the reference nor the arm's momentum carries the TCP through:
//
//   reference  before the law, the law's command (a command's or a chunk's reference alike) has
//              its position projected back onto the allowed region, and the components of its
//              twist and acceleration out through a wall it lies on removed; near a wall (within
//              wall.brake_distance_m of the measured TCP) the feedforward force's component
//              out through it is removed as well. The law then pulls toward a point inside.
//   barrier    after the law and the governor, a TCP within brake_distance_m of a wall and
//              moving toward it is braked by F = -n (k e min(u / 0.02 m/s, 1) + c u) (e the
//              depth into the braking zone, u the approach speed), added as J^T F to the torque
//              and scaled into the effort limits (wrench_bound.hpp). It acts only while the TCP
//              approaches, so it only takes energy out (F . v <= 0): it cannot push the arm
//              anywhere, and a TCP at rest near a wall feels nothing.
//
// Dimensioning (the defaults, FR3). The reference stops at the wall, so what must be stopped is
// the TCP's momentum and the law's pull over the last brake_distance: at the TCP the FR3's
// apparent mass is at most ~ m = 5 kg in its usual workspace (2 to 4 kg across it, more near a
// singularity). Damping alone stops a TCP arriving at speed v within m v / c: 5 x 0.5 / 200 =
// 12.5 mm, a quarter of the 50 mm zone, and the spring, k e at most 100 N by the wall, takes
// care of a law pulling harder than the damper brakes. Peak force ~ c v + k e ~ 100 + 100 N, within
// what the FR3's joints give at the TCP (the effort bound scales it otherwise). Faster than
// ~ c b / m = 2 m/s (twice the governor's TCP speed) the zone alone would not suffice. At 1 kHz,
// c T / m = 0.08 on the FR3's lightest apparent mass at the TCP (2.6 kg): far from deadbeat, so the
// damper is stable; resolving refuses a c past half of deadbeat, m / (2 T), on the robot's own.
// Measured in the simulated FR3 (tests/sim/virtual_walls_test.cpp, docs/safety.md): see there.
//
// Real-time: allocates nothing, takes no lock, never throws.

#include "comply/core/commands.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wall_geometry.hpp"
#include "comply/plugin/abi.h"

namespace comply::pipeline {

class VirtualWalls {
 public:
  /// `cartesian`: the law takes Cartesian commands (walls need a TCP reference).
  VirtualWalls(const CycleParameters& parameters, bool cartesian);

  [[nodiscard]] bool enabled() const noexcept { return enabled_; }

  /// The box of the command in force (workspace_min, workspace_max; all 0: none), in force from
  /// this cycle on besides the file's walls. Unchanged, it costs six comparisons.
  void commandBox(const double* min, const double* max) noexcept;
  /// The commanded box in force, and whether there is one.
  [[nodiscard]] bool boxCommanded() const noexcept { return box_commanded_; }
  [[nodiscard]] const WallBox& box() const noexcept { return box_; }

  /// The reference: `out` = `in` kept inside the walls (see above), the measured TCP at
  /// `tcp_position`. True when anything changed, and only then is `out` written (the law may
  /// read `in` itself otherwise).
  bool limitReference(const comply_cartesian_command& in, const Eigen::Vector3d& tcp_position,
                      comply_cartesian_command& out) noexcept;

  /// The barrier: adds J^T F to `torque` for the TCP at `data`'s pose moving at `tcp_twist`.
  /// True when a force acted.
  bool brake(const model::Data& data, const Vector6d& tcp_twist, int dof,
             JointVector& torque) noexcept;

  /// A cycle without the barrier (FAULT's hold): the distance from the TCP at `tcp_position`,
  /// measured this cycle, and no force, so the state never shows a stale barrier.
  void observe(const Eigen::Vector3d& tcp_position) noexcept;

  /// The last cycle's distance from the measured TCP to the nearest wall or face [m] (negative
  /// past one) and the barrier's force [N, base frame].
  [[nodiscard]] double distance() const noexcept { return distance_m_; }
  [[nodiscard]] const Eigen::Vector3d& force() const noexcept { return force_n_; }

  /// The distance and force back to none; a commanded box stays, as the command in force does.
  void reset() noexcept;

 private:
  /// The file's walls, with the commanded box's faces when there is one.
  [[nodiscard]] const WallSet& walls() const noexcept {
    return box_commanded_ ? with_box_ : parameters_.walls.set;
  }

  const CycleParameters& parameters_;
  bool cartesian_ = false;
  bool enabled_ = false;
  bool box_commanded_ = false;
  WallBox box_;
  WallSet with_box_;
  double distance_m_ = 0.0;
  Eigen::Vector3d force_n_ = Eigen::Vector3d::Zero();
};

}  // namespace comply::pipeline
