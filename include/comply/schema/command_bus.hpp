#pragma once
// Interim reference rules on the plugin buses (replaced by the schema table's).

#include <cstring>

#include "comply/core/state.hpp"
#include "comply/plugin/abi.h"

namespace comply::schema {

inline void mergeBus(comply_joint_command& into, const comply_joint_command& in) noexcept {
  const auto copy = [&](std::uint32_t group, double* to, const double* from) {
    if ((in.fields & group) != 0) {
      std::memcpy(to, from, sizeof(double) * COMPLY_MAX_DOF);
    }
  };
  into.stamp_s = in.stamp_s;
  into.dof = in.dof;
  copy(COMPLY_FIELD_POSITION, into.position, in.position);
  copy(COMPLY_FIELD_VELOCITY, into.velocity, in.velocity);
  copy(COMPLY_FIELD_ACCELERATION, into.acceleration, in.acceleration);
  copy(COMPLY_FIELD_STIFFNESS, into.stiffness, in.stiffness);
  copy(COMPLY_FIELD_DAMPING, into.damping, in.damping);
  copy(COMPLY_FIELD_TORQUE_FEEDFORWARD, into.torque_feedforward, in.torque_feedforward);
}

inline void mergeBus(comply_cartesian_command& into, const comply_cartesian_command& in) noexcept {
  const auto copy = [&](std::uint32_t group, double* to, const double* from, int n) {
    if ((in.fields & group) != 0) {
      std::memcpy(to, from, sizeof(double) * n);
    }
  };
  into.stamp_s = in.stamp_s;
  into.dof = in.dof;
  copy(COMPLY_FIELD_POSITION, into.position, in.position, 3);
  copy(COMPLY_FIELD_POSITION, into.orientation, in.orientation, 4);
  copy(COMPLY_FIELD_VELOCITY, into.twist, in.twist, 6);
  copy(COMPLY_FIELD_ACCELERATION, into.acceleration, in.acceleration, 6);
  copy(COMPLY_FIELD_STIFFNESS, into.stiffness_translational, in.stiffness_translational, 9);
  copy(COMPLY_FIELD_STIFFNESS, into.stiffness_rotational, in.stiffness_rotational, 9);
  copy(COMPLY_FIELD_DAMPING, into.damping_translational, in.damping_translational, 9);
  copy(COMPLY_FIELD_DAMPING, into.damping_rotational, in.damping_rotational, 9);
  copy(COMPLY_FIELD_DAMPING, into.damping_ratio, in.damping_ratio, 6);
  if ((in.fields & COMPLY_FIELD_DAMPING) != 0) {
    into.damping_mode = in.damping_mode;
  }
  copy(COMPLY_FIELD_TASK_FRAME, into.task_frame, in.task_frame, 4);
  copy(COMPLY_FIELD_WRENCH_FEEDFORWARD, into.wrench_feedforward, in.wrench_feedforward, 6);
  copy(COMPLY_FIELD_TORQUE_FEEDFORWARD, into.torque_feedforward, in.torque_feedforward,
       COMPLY_MAX_DOF);
  copy(COMPLY_FIELD_NULLSPACE, into.nullspace_position, in.nullspace_position, COMPLY_MAX_DOF);
  copy(COMPLY_FIELD_NULLSPACE, into.nullspace_stiffness, in.nullspace_stiffness, COMPLY_MAX_DOF);
  copy(COMPLY_FIELD_NULLSPACE, into.nullspace_damping, in.nullspace_damping, COMPLY_MAX_DOF);
}

inline void seedReference(comply_joint_command& bus, const MeasuredPose& pose) noexcept {
  for (int i = 0; i < COMPLY_MAX_DOF; ++i) {
    bus.position[i] = i < pose.position.size() ? pose.position[i] : 0.0;
    bus.velocity[i] = 0.0;
    bus.acceleration[i] = 0.0;
  }
}

inline void seedReference(comply_cartesian_command& bus, const MeasuredPose& pose) noexcept {
  for (int k = 0; k < 3; ++k) {
    bus.position[k] = pose.tcp_position[k];
  }
  bus.orientation[0] = pose.tcp_orientation.x();
  bus.orientation[1] = pose.tcp_orientation.y();
  bus.orientation[2] = pose.tcp_orientation.z();
  bus.orientation[3] = pose.tcp_orientation.w();
  for (int k = 0; k < 6; ++k) {
    bus.twist[k] = 0.0;
    bus.acceleration[k] = 0.0;
  }
  for (int i = 0; i < pose.position.size(); ++i) {
    bus.nullspace_position[i] = pose.position[i];
  }
}

inline void stopMotion(comply_joint_command& bus) noexcept {
  for (int i = 0; i < COMPLY_MAX_DOF; ++i) {
    bus.velocity[i] = 0.0;
    bus.acceleration[i] = 0.0;
  }
}

inline void stopMotion(comply_cartesian_command& bus) noexcept {
  for (int k = 0; k < 6; ++k) {
    bus.twist[k] = 0.0;
    bus.acceleration[k] = 0.0;
  }
}

}  // namespace comply::schema

#include "comply/core/commands.hpp"

namespace comply::schema {

inline JointCommand fromBus(const comply_joint_command& bus) {
  JointCommand command = JointCommand::zero(bus.dof);
  command.stamp_s = bus.stamp_s;
  command.fields = static_cast<CommandField>(bus.fields);
  for (int i = 0; i < bus.dof; ++i) {
    command.position[i] = bus.position[i];
    command.velocity[i] = bus.velocity[i];
    command.acceleration[i] = bus.acceleration[i];
    command.stiffness[i] = bus.stiffness[i];
    command.damping[i] = bus.damping[i];
    command.torque_feedforward[i] = bus.torque_feedforward[i];
  }
  return command;
}

inline CartesianCommand fromBus(const comply_cartesian_command& bus) {
  using RowMajor = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  const auto quaternion = [](const double* xyzw) {
    return Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
  };
  CartesianCommand command = CartesianCommand::zero(bus.dof);
  command.stamp_s = bus.stamp_s;
  command.fields = static_cast<CommandField>(bus.fields);
  command.position = Eigen::Map<const Eigen::Vector3d>(bus.position);
  command.orientation = quaternion(bus.orientation);
  command.twist = Eigen::Map<const Vector6d>(bus.twist);
  command.acceleration = Eigen::Map<const Vector6d>(bus.acceleration);
  command.stiffness_translational = Eigen::Map<const RowMajor>(bus.stiffness_translational);
  command.stiffness_rotational = Eigen::Map<const RowMajor>(bus.stiffness_rotational);
  command.damping_translational = Eigen::Map<const RowMajor>(bus.damping_translational);
  command.damping_rotational = Eigen::Map<const RowMajor>(bus.damping_rotational);
  command.damping_mode = static_cast<DampingMode>(bus.damping_mode);
  command.damping_ratio = Eigen::Map<const Vector6d>(bus.damping_ratio);
  command.task_frame = quaternion(bus.task_frame);
  command.wrench_feedforward = Eigen::Map<const Vector6d>(bus.wrench_feedforward);
  for (int i = 0; i < bus.dof; ++i) {
    command.torque_feedforward[i] = bus.torque_feedforward[i];
    command.nullspace_position[i] = bus.nullspace_position[i];
    command.nullspace_stiffness[i] = bus.nullspace_stiffness[i];
    command.nullspace_damping[i] = bus.nullspace_damping[i];
  }
  return command;
}

}  // namespace comply::schema
