#include "comply/pipeline/workspace_intake.hpp"

#include <sstream>
#include <string>

#include "comply/pipeline/wall_geometry.hpp"

namespace comply::pipeline {
namespace {

// The file's walls and the box meet when the alternating projections end inside both within
// this [m]; they converge exactly for walls at right angles, geometrically otherwise.
constexpr double kRoomTolerance_m = 1e-6;

Verdict reject(const std::string& message) {
  return {false, RejectionReason::kInvalidWorkspace,
          std::string(toString(RejectionReason::kInvalidWorkspace)) + ": " + message};
}

std::string point(const Eigen::Vector3d& p) {
  std::ostringstream text;
  text << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") m";
  return text.str();
}

}  // namespace

Verdict checkWorkspace(const CartesianCommand& command, const CycleParameters& parameters,
                       const MeasuredPose& measured) {
  if (!has(command.fields, CommandField::kWorkspace)) {
    return {};
  }
  const WallBox box{command.workspace_min, command.workspace_max};
  if (box.min.isZero(0.0) && box.max.isZero(0.0)) {
    return {};  // no box: the file's walls alone
  }
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!(box.min[i] < box.max[i])) {
      std::ostringstream text;
      text << "workspace_min along " << kAxes[i] << " (" << box.min[i]
           << " m) is not below workspace_max (" << box.max[i] << " m)";
      return reject(text.str());
    }
  }
  const double zone_m = parameters.walls.gains.brake_distance_m;
  // The box's point nearest the TCP (its centre before anything was measured).
  const Eigen::Vector3d nearest =
      measured.valid ? Eigen::Vector3d(measured.tcp_position.cwiseMax(box.min).cwiseMin(box.max))
                     : Eigen::Vector3d(0.5 * (box.min + box.max));
  if (measured.valid) {
    const double outside_m = (measured.tcp_position - nearest).norm();
    if (outside_m > zone_m) {
      std::ostringstream text;
      text << "the TCP at " << point(measured.tcp_position) << " is " << outside_m
           << " m outside the box " << point(box.min) << " to " << point(box.max)
           << "; a box must hold the TCP, or lie within wall.brake_distance_m (" << zone_m
           << " m) of it";
      return reject(text.str());
    }
  }
  if (!parameters.walls.set.empty()) {
    WallSet both = parameters.walls.set;
    (void)appendBox(box, both);  // the file's are at most kMaxWallPlanes: room for six
    Eigen::Vector3d probe = nearest;
    (void)projectInside(both, probe);
    if (nearestWallDistance(both, probe) < -kRoomTolerance_m) {
      return reject("the box " + point(box.min) + " to " + point(box.max) +
                    " leaves no room inside the controller file's walls and boxes");
    }
  }
  return {};
}

}  // namespace comply::pipeline
