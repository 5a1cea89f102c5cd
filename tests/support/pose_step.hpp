#pragma once
// The step many Cartesian tests give an arm at rest: a position target a few centimetres from
// where the wrapper measures the TCP, its orientation held.

#include <Eigen/Core>

#include "comply/pipeline/wrapper.hpp"

namespace comply::testing {

/// A position command `offset_m` [m, base frame] from the measured TCP, orientation as measured.
inline CartesianCommand poseStep(const pipeline::CartesianWrapper& wrapper,
                                 const Eigen::Vector3d& offset_m, double stamp_s = 1.0) {
  CartesianCommand target = CartesianCommand::zero(wrapper.dof());
  target.stamp_s = stamp_s;
  target.fields = CommandField::kPosition;
  target.position = wrapper.measuredPose().tcp_position + offset_m;
  target.orientation = wrapper.measuredPose().tcp_orientation;
  return target;
}

}  // namespace comply::testing
