// Output mode joint_pd: the cycle's torque split into what a drive with an onboard PD takes,
//   tau = kp (q_d - q) + kd (dq_d - dq) + tau_ff,
// equal to the torque at the sample by construction (tau_ff is the remainder). Between two
// samples the drive runs its PD at its own rate, so kp and kd are chosen as the law's own
// stiffness and damping around the sample (the diagonal of -d tau/d q and -d tau/d dq):
//   joint law      kp, kd, q_d, dq_d are the command's (diagonal gains: exact, up to the
//                  compensation terms, which stay in tau_ff);
//   Cartesian law  kp_i = J_i^T K J_i and kd_i = J_i^T D J_i with K, D in the base frame, about
//                  the measured q, dq (q_d = q, dq_d = dq). Approximate: the couplings between
//                  joints, the change of J and the nullspace spring stay in tau_ff, held over
//                  the period. With damping ratios, kd_i = 2 zeta sqrt(kp_i M_ii), zeta the mean
//                  of the six ratios.
// In FAULT the drive gets the holding torque alone (kp = kd = 0), as torque mode does.

#include <cmath>

#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/output_stage.hpp"

namespace comply::pipeline {
namespace {

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

/// u^T R A R^T u for a task-frame block A: the block's stiffness along the base vector u.
double along(const Eigen::Vector3d& u, const Eigen::Matrix3d& task_to_base, const double* block) {
  const Eigen::Vector3d in_task = task_to_base.transpose() * u;
  return in_task.dot(Eigen::Map<const RowMajor3>(block) * in_task);
}

}  // namespace

void OutputStage::cartesianJointGains(const Controller& controller, const JointState& state,
                                      ActuatorCommand& command) const noexcept {
  const auto* law = std::get_if<comply_cartesian_command>(&controller.lawBus());
  if (law == nullptr) {
    return;  // cannot happen: a Cartesian controller's bus is Cartesian
  }
  const comply_cartesian_command& bus = *law;
  const model::Data& data = controller.modelData();
  const Eigen::Matrix3d task_to_base = taskToBase(bus);
  double mean_ratio = 0.0;
  for (const double ratio : bus.damping_ratio) {
    mean_ratio += ratio / 6.0;
  }
  for (int i = 0; i < dof_; ++i) {
    const Eigen::Vector3d linear = data.jacobian.col(i).head<3>();
    const Eigen::Vector3d angular = data.jacobian.col(i).tail<3>();
    const double kp = along(linear, task_to_base, bus.stiffness_translational) +
                      along(angular, task_to_base, bus.stiffness_rotational);
    command.stiffness[i] = std::max(kp, 0.0);
    command.damping[i] =
        bus.damping_mode == COMPLY_DAMPING_RATIO
            ? 2.0 * mean_ratio * std::sqrt(command.stiffness[i] * data.mass_matrix(i, i))
            : std::max(along(linear, task_to_base, bus.damping_translational) +
                           along(angular, task_to_base, bus.damping_rotational),
                       0.0);
    command.position[i] = state.position[i];
    command.velocity[i] = state.velocity[i];
  }
}

void OutputStage::splitForJointPd(const Controller& controller, bool fault, const JointState& state,
                                  ActuatorCommand& command) const noexcept {
  const bool finite = state.usable(dof_);
  if (fault || !finite) {
    for (int i = 0; i < dof_; ++i) {
      command.stiffness[i] = 0.0;
      command.damping[i] = 0.0;
      command.position[i] = finite ? state.position[i] : 0.0;
      command.velocity[i] = 0.0;
    }
    return;  // tau_ff = the holding torque, already in command.effort
  }
  if (cartesian_) {
    cartesianJointGains(controller, state, command);
  } else {
    const auto* bus = std::get_if<comply_joint_command>(&controller.lawBus());
    for (int i = 0; i < dof_ && bus != nullptr; ++i) {
      command.stiffness[i] = bus->stiffness[i];
      command.damping[i] = bus->damping[i];
      command.position[i] = bus->position[i];
      command.velocity[i] = bus->velocity[i];
    }
  }
  for (int i = 0; i < dof_; ++i) {
    command.effort[i] -= command.stiffness[i] * (command.position[i] - state.position[i]) +
                         command.damping[i] * (command.velocity[i] - state.velocity[i]);
  }
}

}  // namespace comply::pipeline
