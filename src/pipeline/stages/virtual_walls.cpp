#include "comply/pipeline/virtual_walls.hpp"

#include <cmath>
#include <limits>

#include "comply/pipeline/wrench_bound.hpp"

namespace comply::pipeline {
namespace {

// A reference this close to a wall is on it: its motion out through the wall is removed. The
// projection puts it on the wall up to rounding; a hair more keeps a reference that arrives
// exactly there from creeping through by one cycle's step.
constexpr double kOnWallTolerance_m = 1e-9;

Eigen::Map<Eigen::Vector3d> vector3(double* values) noexcept {
  return Eigen::Map<Eigen::Vector3d>(values);
}

}  // namespace

VirtualWalls::VirtualWalls(const CycleParameters& parameters, bool cartesian)
    : parameters_(parameters),
      cartesian_(cartesian),
      enabled_(cartesian && !parameters.walls.set.empty()) {
  reset();
}

void VirtualWalls::commandBox(const double* min, const double* max) noexcept {
  const Eigen::Map<const Eigen::Vector3d> lower(min);
  const Eigen::Map<const Eigen::Vector3d> upper(max);
  const bool none = lower.isZero(0.0) && upper.isZero(0.0);
  if (none ? !box_commanded_ : (box_commanded_ && lower == box_.min && upper == box_.max)) {
    return;
  }
  box_commanded_ = !none;
  box_ = none ? WallBox{} : WallBox{lower, upper};
  with_box_ = parameters_.walls.set;
  if (box_commanded_) {
    (void)appendBox(box_, with_box_);  // the file's are at most kMaxWallPlanes: room for six
  }
  enabled_ = cartesian_ && !walls().empty();
}

void VirtualWalls::reset() noexcept {
  distance_m_ = std::numeric_limits<double>::infinity();
  force_n_.setZero();
}

bool VirtualWalls::limitReference(const comply_cartesian_command& in,
                                  const Eigen::Vector3d& tcp_position,
                                  comply_cartesian_command& out) noexcept {
  const WallSet& set = walls();
  Eigen::Vector3d position(in.position[0], in.position[1], in.position[2]);
  bool changed = projectInside(set, position);
  Eigen::Vector3d velocity(in.twist[0], in.twist[1], in.twist[2]);
  Eigen::Vector3d acceleration(in.acceleration[0], in.acceleration[1], in.acceleration[2]);
  changed = removeOutward(set, position, kOnWallTolerance_m, velocity, acceleration) || changed;
  // A feedforward force pushes whatever the reference: near a wall, none of it outward.
  Eigen::Vector3d push(in.wrench_feedforward[0], in.wrench_feedforward[1],
                       in.wrench_feedforward[2]);
  changed =
      removeOutward(set, tcp_position, parameters_.walls.gains.brake_distance_m, push) || changed;
  if (!changed) {
    return false;  // the law reads `in` itself: no copy of the command
  }
  out = in;
  vector3(out.position) = position;
  vector3(out.twist) = velocity;
  vector3(out.acceleration) = acceleration;
  vector3(out.wrench_feedforward) = push;
  return true;
}

void VirtualWalls::observe(const Eigen::Vector3d& tcp_position) noexcept {
  distance_m_ = nearestWallDistance(walls(), tcp_position);
  force_n_.setZero();
}

bool VirtualWalls::brake(const model::Data& data, const Vector6d& tcp_twist, int dof,
                         JointVector& torque) noexcept {
  const WallSet& set = walls();
  force_n_ = barrierForce(set, parameters_.walls.gains, data.tip_position, tcp_twist.head<3>(),
                          &distance_m_);
  if (force_n_.isZero(0.0) || !force_n_.allFinite()) {
    force_n_.setZero();
    return false;
  }
  Vector6d wrench = Vector6d::Zero();
  wrench.head<3>() = force_n_;
  // Within what the joints give at this pose, its direction kept (the shaper's effort limit
  // would turn it).
  (void)boundWrench(data.jacobian, wrench.data(), parameters_.effort_limit, dof);
  force_n_ = wrench.head<3>();
  torque.head(dof).noalias() += data.jacobian.leftCols(dof).transpose() * wrench;
  return true;
}

}  // namespace comply::pipeline
