// The virtual arm of the admittance modes (virtual_arm.hpp).

#include "comply/pipeline/virtual_arm.hpp"

#include <algorithm>
#include <cmath>

#include "comply/core/rotation.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/output_stage.hpp"

namespace comply::pipeline {

VirtualArm::VirtualArm(const ResolvedController& resolved)
    : parameters_(resolved.parameters),
      dof_(resolved.dof),
      velocity_mode_(resolved.parameters.output.mode == OutputMode::kVelocity),
      added_inertia_(
          (resolved.parameters.output.admittance.added_mass_kg.array() > 0.0).any() ||
          (resolved.parameters.output.admittance.added_inertia_kg_m2.array() > 0.0).any()) {
  virtual_ = JointState::zero(dof_);
  last_measured_.setZero(dof_);
  hold_position_.setZero(dof_);
  inertia_.setZero(dof_, dof_);
  virtual_torque_.setZero(dof_);
  acceleration_.setZero(dof_);
}

void VirtualArm::reset(const JointState& state) noexcept {
  virtual_.position = state.position;
  virtual_.velocity = state.velocity;
  virtual_.effort.setZero(dof_);
  last_measured_ = state.position;
  acceleration_.setZero(dof_);
  holding_ = false;
}

const JointState& VirtualArm::lawState(const JointState& measured) noexcept {
  const bool usable = measured.usable(dof_);
  if (usable) {
    last_measured_ = measured.position;
    keepNearMeasured(measured);
  }
  virtual_.wrench = measured.wrench;  // the raw reading: the controller takes the tool and tare off
  virtual_.wrench_valid = measured.wrench_valid;
  virtual_.robot_stop = measured.robot_stop;  // the robot's own stop is the law's FAULT too
  return usable ? virtual_ : measured;
}

void VirtualArm::step(const Controller& controller, const JointState& measured, double period_s,
                      ActuatorCommand& command) noexcept {
  holding_ = false;
  integrate(controller, period_s, command);
  writeMotion(measured, command);
}

void VirtualArm::keepNearMeasured(const JointState& state) noexcept {
  const double bound = parameters_.output.admittance.max_tracking_error_rad;
  for (int i = 0; i < dof_; ++i) {
    const double error = virtual_.position[i] - state.position[i];
    if (std::abs(error) > bound) {
      virtual_.position[i] = state.position[i] + std::copysign(bound, error);
      if (virtual_.velocity[i] * error > 0.0) {
        virtual_.velocity[i] = 0.0;  // moving further away: stop winding up
      }
    }
  }
}

void VirtualArm::integrate(const Controller& controller, double period_s,
                           const ActuatorCommand& command) noexcept {
  const AdmittanceConfig& admittance = parameters_.output.admittance;
  const model::Data& data = controller.modelData();
  const auto n = static_cast<Eigen::Index>(dof_);
  virtual_torque_ = command.effort.head(n);
  inertia_ = data.mass_matrix.topLeftCorner(n, n);
  external_ = controller.sensorWrenchValid() ? controller.sensorWrench() : Vector6d::Zero();
  if (parameters_.payload_on_sensor && parameters_.payload.mass_kg > 0.0) {
    addPayload(data, controller.sensorWrenchValid());
  }
  virtual_torque_.noalias() += data.jacobian.leftCols(n).transpose() * external_;
  if (added_inertia_) {
    addInertia(controller);
  }
  inertia_solver_.compute(inertia_);
  acceleration_ = inertia_solver_.solve(virtual_torque_);

  if (!acceleration_.allFinite()) {
    acceleration_.setZero(dof_);
  }
  for (int i = 0; i < dof_; ++i) {
    const double max_speed = admittance.velocity_factor * parameters_.velocity_limit[i];
    acceleration_[i] = std::clamp(acceleration_[i], -admittance.max_acceleration_rad_per_s2,
                                  admittance.max_acceleration_rad_per_s2);
    virtual_.velocity[i] =
        std::clamp(virtual_.velocity[i] + acceleration_[i] * period_s, -max_speed, max_speed);
  }
  const SoftLimitParameters& limits = parameters_.soft_limits;
  for (int i = 0; i < dof_; ++i) {
    double& q = virtual_.position[i];
    q += virtual_.velocity[i] * period_s;
    if (q < limits.lower[i] || q > limits.upper[i]) {
      q = std::clamp(q, limits.lower[i], limits.upper[i]);
      virtual_.velocity[i] = 0.0;
    }
  }
}

void VirtualArm::addInertia(const Controller& controller) noexcept {
  const AdmittanceConfig& admittance = parameters_.output.admittance;
  const model::Data& data = controller.modelData();
  const auto n = static_cast<Eigen::Index>(dof_);
  Eigen::Matrix3d task_to_base = Eigen::Matrix3d::Identity();
  if (const auto* bus = std::get_if<comply_cartesian_command>(&controller.lawBus())) {
    task_to_base = taskToBase(*bus);
  }
  // J^T A J with A = R diag(a) R^T: (diag(sqrt a) R^T J)^T (diag(sqrt a) R^T J).
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, kMaxDof> weighted(3, n);
  weighted.noalias() = admittance.added_mass_kg.cwiseSqrt().asDiagonal() *
                       task_to_base.transpose() * data.jacobian.topLeftCorner(3, n);
  inertia_.noalias() += weighted.transpose() * weighted;
  weighted.noalias() = admittance.added_inertia_kg_m2.cwiseSqrt().asDiagonal() *
                       task_to_base.transpose() * data.jacobian.bottomLeftCorner(3, n);
  inertia_.noalias() += weighted.transpose() * weighted;
}

void VirtualArm::addPayload(const model::Data& data, bool sensed) noexcept {
  // The sensor's reading carries the payload's inertial force -m a_com; it is given that force
  // back from the virtual arm's last acceleration (what the drives follow), with the centre of
  // mass moving by J_com = J_linear - [r]x J_angular. The payload's mass joins the virtual arm:
  // without it, that return of force is a positive feedback of the acceleration with gain
  // m / (the arm's own inertia along the motion), which diverges for a payload heavier than the
  // wrist. (A law with damping ratios still damps against the arm's own inertia, so a declared
  // payload lowers the ratio by sqrt(arm / (arm + payload)) along each direction.)
  const auto n = static_cast<Eigen::Index>(dof_);
  const double mass = parameters_.payload.mass_kg;
  const Eigen::Vector3d arm = data.tip_rotation * parameters_.payload.com_in_tip;
  const Eigen::Matrix3d cross = skew(arm);
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, kMaxDof> com_jacobian(3, n);
  com_jacobian.noalias() = data.jacobian.topLeftCorner(3, n);
  com_jacobian.noalias() -= cross * data.jacobian.bottomLeftCorner(3, n);
  inertia_.noalias() += mass * com_jacobian.transpose() * com_jacobian;
  if (sensed) {
    const Eigen::Vector3d inertial_force = mass * (com_jacobian * acceleration_.head(n));
    external_.head<3>() += inertial_force;
    external_.tail<3>() += arm.cross(inertial_force);
  }
}

void VirtualArm::writeMotion(const JointState& state, ActuatorCommand& command) const noexcept {
  const double correction = parameters_.output.admittance.velocity_correction_per_s;
  for (int i = 0; i < dof_; ++i) {
    command.position[i] = virtual_.position[i];
    command.velocity[i] =
        velocity_mode_
            ? virtual_.velocity[i] + correction * (virtual_.position[i] - state.position[i])
            : virtual_.velocity[i];
  }
}

void VirtualArm::hold(const JointState& state, ActuatorCommand& command) noexcept {
  // While the robot says it is stopped, the arm may be moved by other means (jogged, guided by
  // hand, coasting after an emergency stop): the hold is where it is now, so that once the robot
  // takes commands again nothing pulls it back to where the FAULT began.
  if (!holding_ || state.robot_stop != nullptr) {
    holding_ = true;
    hold_position_ = last_measured_;
  }
  virtual_.position = hold_position_;
  virtual_.velocity.setZero(dof_);
  const bool measured = state.usable(dof_);
  const double correction = parameters_.output.admittance.velocity_correction_per_s;
  for (int i = 0; i < dof_; ++i) {
    command.position[i] = hold_position_[i];
    command.velocity[i] =
        velocity_mode_ && measured ? correction * (hold_position_[i] - state.position[i]) : 0.0;
  }
}

}  // namespace comply::pipeline
