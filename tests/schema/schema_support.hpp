#pragma once
// Commands with a distinct value in every field, so that a swapped, transposed or dropped field
// shows in a bit-for-bit comparison.

#include <bit>
#include <cstdint>
#include <cstring>

#include "comply/core/commands.hpp"

namespace comply::schema::test {

constexpr int kDof = 3;

inline JointVector ramp(double start, int dof = kDof) {
  JointVector v(dof);
  for (int i = 0; i < dof; ++i) {
    v[i] = start + 0.25 * i;
  }
  return v;
}

/// Symmetric positive definite, and not diagonal (a transposed copy would still be equal, but a
/// reordered one would not).
inline Eigen::Matrix3d gains(double scale) {
  Eigen::Matrix3d m;
  m << 4, 1, 0.5, 1, 3, 0.25, 0.5, 0.25, 2;
  return scale * m;
}

inline CartesianCommand distinctCartesian() {
  CartesianCommand c = CartesianCommand::zero(kDof);
  c.stamp_s = 1.25;
  c.position = {0.1, -0.2, 0.3};
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  c.twist << 1, 2, 3, 4, 5, 6;
  c.acceleration << 7, 8, 9, 10, 11, 12;
  c.stiffness_translational = gains(100);
  c.stiffness_rotational = gains(10);
  c.damping_translational = gains(3);
  c.damping_rotational = gains(0.5);
  c.damping_mode = DampingMode::kRatio;
  c.damping_ratio << 0.5, 0.6, 0.7, 0.8, 0.9, 1.1;
  c.task_frame = Eigen::Quaterniond(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(0, 1, 1).normalized()));
  c.wrench_feedforward << -1, -2, -3, -4, -5, -6;
  c.torque_feedforward = ramp(10);
  c.nullspace_position = ramp(20);
  c.nullspace_stiffness = ramp(30);
  c.nullspace_damping = ramp(40);
  c.force_axes << 1, 0, 1, 0, 0, 1;
  c.wrench_target << 7, -8, 9, -0.7, 0.8, -0.9;
  c.reflex_force << 21, 0, 45;
  c.reflex_torque << 0, 3.5, 6;
  c.workspace_min << 0.25, -0.5, 0.125;
  c.workspace_max << 0.75, 0.5, 0.875;
  return c;
}

inline JointCommand distinctJoint() {
  JointCommand c = JointCommand::zero(kDof);
  c.stamp_s = 2.5;
  c.position = ramp(0.1);
  c.velocity = ramp(-1.0);
  c.acceleration = ramp(5.0);
  c.stiffness = ramp(100.0);
  c.damping = ramp(10.0);
  c.torque_feedforward = ramp(-3.0);
  c.reflex_force << 0, 25, 31;
  c.reflex_torque << 4.5, 0, 2;
  return c;
}

/// Same bytes: the C buses are plain data, zero-initialised, so memcmp compares every field.
template <typename Bus>
bool sameBytes(const Bus& a, const Bus& b) {
  return std::memcmp(&a, &b, sizeof(Bus)) == 0;
}

}  // namespace comply::schema::test
