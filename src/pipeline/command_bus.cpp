#include "comply/pipeline/command_bus.hpp"

#include <algorithm>

namespace comply::pipeline {
namespace {

static_assert(static_cast<std::uint32_t>(CommandField::kPosition) == COMPLY_FIELD_POSITION);
static_assert(static_cast<std::uint32_t>(CommandField::kNullspace) == COMPLY_FIELD_NULLSPACE);
static_assert(static_cast<int>(DampingMode::kRatio) == COMPLY_DAMPING_RATIO);
static_assert(kMaxDof == COMPLY_MAX_DOF, "core capacity and ABI capacity must agree");

void copyRowMajor(const Eigen::Matrix3d& m, double* out) {
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> target(out);
  target = m;
}

void copyQuaternion(const Eigen::Quaterniond& q, double* xyzw) {
  xyzw[0] = q.x();
  xyzw[1] = q.y();
  xyzw[2] = q.z();
  xyzw[3] = q.w();
}

void copyJoints(const JointVector& v, int dof, double* out) {
  for (int i = 0; i < dof; ++i) {
    out[i] = i < v.size() ? v[i] : 0.0;
  }
}

}  // namespace

comply_cartesian_command toBus(const CartesianCommand& command, int dof) {
  comply_cartesian_command bus{};
  bus.stamp_s = command.stamp_s;
  bus.fields = static_cast<std::uint32_t>(command.fields);
  bus.dof = dof;
  Eigen::Map<Eigen::Vector3d>(bus.position) = command.position;
  copyQuaternion(command.orientation, bus.orientation);
  Eigen::Map<Vector6d>(bus.twist) = command.twist;
  Eigen::Map<Vector6d>(bus.acceleration) = command.acceleration;
  copyRowMajor(command.stiffness_translational, bus.stiffness_translational);
  copyRowMajor(command.stiffness_rotational, bus.stiffness_rotational);
  copyRowMajor(command.damping_translational, bus.damping_translational);
  copyRowMajor(command.damping_rotational, bus.damping_rotational);
  bus.damping_mode = static_cast<int32_t>(command.damping_mode);
  Eigen::Map<Vector6d>(bus.damping_ratio) = command.damping_ratio;
  copyQuaternion(command.task_frame, bus.task_frame);
  Eigen::Map<Vector6d>(bus.wrench_feedforward) = command.wrench_feedforward;
  copyJoints(command.torque_feedforward, dof, bus.torque_feedforward);
  copyJoints(command.nullspace_position, dof, bus.nullspace_position);
  copyJoints(command.nullspace_stiffness, dof, bus.nullspace_stiffness);
  copyJoints(command.nullspace_damping, dof, bus.nullspace_damping);
  return bus;
}

comply_joint_command toBus(const JointCommand& command, int dof) {
  comply_joint_command bus{};
  bus.stamp_s = command.stamp_s;
  bus.fields = static_cast<std::uint32_t>(command.fields);
  bus.dof = dof;
  copyJoints(command.position, dof, bus.position);
  copyJoints(command.velocity, dof, bus.velocity);
  copyJoints(command.acceleration, dof, bus.acceleration);
  copyJoints(command.stiffness, dof, bus.stiffness);
  copyJoints(command.damping, dof, bus.damping);
  copyJoints(command.torque_feedforward, dof, bus.torque_feedforward);
  return bus;
}

}  // namespace comply::pipeline
