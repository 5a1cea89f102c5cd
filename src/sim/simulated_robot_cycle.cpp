// The simulated arm each control cycle: its sensors read, its drives commanded, the physics
// stepped (the scene and the drives are set up in simulated_robot.cpp).

#include <algorithm>
#include <cmath>

#include "comply/sim/simulated_robot.hpp"

namespace comply::sim {

bool SimulatedRobot::read(JointState& state) noexcept {
  read_sequence_ = steps_;
  const auto n = static_cast<Eigen::Index>(qpos_address_.size());
  state.position.resize(n);
  state.velocity.resize(n);
  state.effort.resize(n);
  for (std::size_t i = 0; i < qpos_address_.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    state.position[row] = data_->qpos[qpos_address_[i]];
    state.velocity[row] = data_->qvel[dof_address_[i]];
    // Before the first step the arm rests: the sensor reads what the drive holds.
    state.effort[row] =
        link_side_torque_ && link_torque_sensed_ ? link_torque_[i] / substeps_ : applied_[i];
    if (position_noise_rad_ > 0.0) {
      state.position[row] += position_noise_rad_ * unit_normal_(noise_generator_);
    }
    if (velocity_noise_rad_per_s_ > 0.0) {
      state.velocity[row] += velocity_noise_rad_per_s_ * unit_normal_(noise_generator_);
    }
  }
  return true;
}

bool SimulatedRobot::write(std::span<const double> torque) noexcept {
  if (torque.size() != applied_.size() ||
      !std::all_of(torque.begin(), torque.end(), [](double t) { return std::isfinite(t); })) {
    return false;
  }
  if (actuation_ == OutputMode::kJointPd) {
    // A PD drive given a torque alone.
    ActuatorCommand command = drive_command_;
    command.mode = OutputMode::kJointPd;
    command.stiffness.setZero();
    command.damping.setZero();
    for (std::size_t i = 0; i < torque.size(); ++i) {
      command.effort[static_cast<Eigen::Index>(i)] = torque[i];
    }
    return writeCommand(command);
  }
  if (actuation_ != OutputMode::kTorque) {
    return false;
  }
  braked_ = false;
  for (std::size_t i = 0; i < torque.size(); ++i) {
    applied_[i] = std::clamp(torque[i], -effort_limit_[i], effort_limit_[i]);
    data_->qfrc_applied[dof_address_[i]] = applied_[i];
  }
  return true;
}

bool SimulatedRobot::accepts(OutputMode mode) const noexcept {
  return mode == actuation_ || (actuation_ == OutputMode::kJointPd && mode == OutputMode::kTorque);
}

bool SimulatedRobot::writeCommand(const ActuatorCommand& command) noexcept {
  if (command.mode == OutputMode::kTorque) {
    return write({command.effort.data(), static_cast<std::size_t>(command.effort.size())});
  }
  const auto dof = static_cast<Eigen::Index>(applied_.size());
  const auto sized_finite = [dof](const JointVector& values) {
    return values.size() == dof && values.allFinite();
  };
  if (command.mode != actuation_ || !sized_finite(command.position) ||
      !sized_finite(command.velocity) ||
      (command.mode == OutputMode::kJointPd &&
       (!sized_finite(command.effort) || !sized_finite(command.stiffness) ||
        !sized_finite(command.damping)))) {
    return false;
  }
  if (braked_ || !drive_commanded_) {
    // The servo takes over from rest where the arm is: no wound-up integral, no old reference.
    std::fill(servo_integral_.begin(), servo_integral_.end(), 0.0);
    for (std::size_t i = 0; i < velocity_reference_.size(); ++i) {
      velocity_reference_[i] = data_->qpos[qpos_address_[i]];
    }
  }
  braked_ = false;
  drive_commanded_ = true;
  drive_command_ = command;
  since_write_s_ = 0.0;
  return true;
}

void SimulatedRobot::driveJoints(double since_write_s) noexcept {
  const double dt = model_->opt.timestep;
  for (std::size_t i = 0; i < applied_.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const double q = data_->qpos[qpos_address_[i]];
    const double dq = data_->qvel[dof_address_[i]];
    double torque = 0.0;
    if (actuation_ == OutputMode::kJointPd) {
      torque = drive_command_.stiffness[row] * (drive_command_.position[row] - q) +
               drive_command_.damping[row] * (drive_command_.velocity[row] - dq) +
               drive_command_.effort[row];
    } else {
      // The reference moves on with its velocity between two commands, as a servo interpolates.
      double reference =
          drive_command_.position[row] + drive_command_.velocity[row] * since_write_s;
      if (actuation_ == OutputMode::kVelocity) {
        velocity_reference_[i] += drive_command_.velocity[row] * dt;
        reference = velocity_reference_[i];
      }
      const double error = reference - q;
      torque = data_->qfrc_bias[dof_address_[i]] + servo_kp_[i] * error +
               servo_ki_[i] * servo_integral_[i] +
               servo_kd_[i] * (drive_command_.velocity[row] - dq);
      if (std::abs(torque) < effort_limit_[i]) {
        servo_integral_[i] += error * dt;  // no wind-up while the drive saturates
      }
    }
    applied_[i] = std::clamp(torque, -effort_limit_[i], effort_limit_[i]);
    data_->qfrc_applied[dof_address_[i]] = applied_[i];
  }
}

bool SimulatedRobot::hold() noexcept {
  drive_commanded_ = false;
  if (!braked_) {
    braked_ = true;
    for (std::size_t i = 0; i < qpos_address_.size(); ++i) {
      held_position_[i] = data_->qpos[qpos_address_[i]];
    }
  }
  return true;
}

void SimulatedRobot::pinHeldJoints() noexcept {
  for (std::size_t i = 0; i < qpos_address_.size(); ++i) {
    data_->qpos[qpos_address_[i]] = held_position_[i];
    data_->qvel[dof_address_[i]] = 0.0;
  }
}

void SimulatedRobot::senseLinkTorque() noexcept {
  // mj_step's forward pass left this substep's constraint forces, passive forces and
  // accelerations in data_: the joint's Coulomb friction is the force of its dof-friction row.
  std::fill(dof_friction_.begin(), dof_friction_.end(), 0.0);
  for (int row = 0; row < data_->nefc; ++row) {
    if (data_->efc_type[row] == mjCNSTR_FRICTION_DOF) {
      dof_friction_[static_cast<std::size_t>(data_->efc_id[row])] += data_->efc_force[row];
    }
  }
  for (std::size_t j = 0; j < dof_address_.size(); ++j) {
    const int dof = dof_address_[j];
    link_torque_[j] += data_->qfrc_applied[dof] + data_->qfrc_passive[dof] +
                       dof_friction_[static_cast<std::size_t>(dof)] -
                       model_->dof_armature[dof] * data_->qacc[dof];
  }
}

void SimulatedRobot::step() noexcept {
  ++steps_;
  std::fill(link_torque_.begin(), link_torque_.end(), 0.0);
  for (int i = 0; i < substeps_; ++i) {
    if (braked_) {
      // The brake: the joints pinned at rest, the drives carrying exactly what holds them there.
      pinHeldJoints();
      mj_forward(model_.get(), data_.get());
      for (std::size_t j = 0; j < dof_address_.size(); ++j) {
        applied_[j] = data_->qfrc_bias[dof_address_[j]];
        data_->qfrc_applied[dof_address_[j]] = applied_[j];
      }
    } else if (actuation_ != OutputMode::kTorque && drive_commanded_) {
      driveJoints(since_write_s_);
      since_write_s_ += model_->opt.timestep;
    }
    applyExternalWrench();
    mj_step(model_.get(), data_.get());
    if (link_side_torque_) {
      senseLinkTorque();
    }
  }
  link_torque_sensed_ = true;
  if (braked_) {
    pinHeldJoints();
    mj_forward(model_.get(), data_.get());
  }
}

void SimulatedRobot::applyExternalWrench() noexcept {
  // MuJoCo applies a body's xfrc_applied at its centre of mass, in world coordinates: the wrench
  // at the TCP is moved there (recomputed every step, as the body turns).
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> base_rotation(
      data_->xmat + 9 * static_cast<std::ptrdiff_t>(base_body_));
  const Eigen::Vector3d force = base_rotation * external_wrench_.head<3>();
  const Eigen::Vector3d torque_at_tcp = base_rotation * external_wrench_.tail<3>();
  const Eigen::Map<const Eigen::Vector3d> tcp(data_->xpos +
                                              3 * static_cast<std::ptrdiff_t>(tip_body_));
  const Eigen::Map<const Eigen::Vector3d> com(data_->xipos +
                                              3 * static_cast<std::ptrdiff_t>(tip_body_));
  Eigen::Map<Eigen::Matrix<double, 6, 1>> applied(data_->xfrc_applied +
                                                  6 * static_cast<std::ptrdiff_t>(tip_body_));
  applied.head<3>() = force;
  applied.tail<3>() = torque_at_tcp + (tcp - com).cross(force);
}

Eigen::Isometry3d SimulatedRobot::tcpPose() const noexcept {
  const auto pose = [&](int body) {
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    // xmat is row-major; Eigen's default is column-major.
    transform.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
        data_->xmat + 9 * static_cast<std::ptrdiff_t>(body));
    transform.translation() =
        Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * static_cast<std::ptrdiff_t>(body));
    return transform;
  };
  return pose(base_body_).inverse() * pose(tip_body_);
}

bool SimulatedRobot::readWrench(Vector6d& wrench) noexcept {
  mj_rnePostConstraint(model_.get(), data_.get());
  // cfrc_int: torque then force, world axes, about the centre of mass of the robot's tree.
  const mjtNum* spatial = data_->cfrc_int + 6 * static_cast<std::ptrdiff_t>(tip_body_);
  const Eigen::Vector3d parent_torque(spatial[0], spatial[1], spatial[2]);
  const Eigen::Vector3d parent_force(spatial[3], spatial[4], spatial[5]);
  const auto point = [](const mjtNum* xyz, int body) {
    return Eigen::Vector3d(
        Eigen::Map<const Eigen::Vector3d>(xyz + 3 * static_cast<std::ptrdiff_t>(body)));
  };
  const Eigen::Vector3d tree_com = point(data_->subtree_com, model_->body_rootid[tip_body_]);
  const Eigen::Vector3d tcp = point(data_->xpos, tip_body_);
  // Parent + environment + weight = m a on the tool: the sensor reads the parent's share with
  // its sign turned, environment + weight - m a.
  const Eigen::Vector3d force_world = -parent_force;
  const Eigen::Vector3d torque_world = -(parent_torque + (tree_com - tcp).cross(parent_force));
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> base_rotation(
      data_->xmat + 9 * static_cast<std::ptrdiff_t>(base_body_));
  const Eigen::Matrix3d tcp_in_base = tcpPose().linear();
  wrench.head<3>() =
      base_rotation.transpose() * force_world + tcp_in_base * wrench_sensor_offset_.head<3>();
  wrench.tail<3>() =
      base_rotation.transpose() * torque_world + tcp_in_base * wrench_sensor_offset_.tail<3>();
  return wrench.allFinite();
}

Vector6d SimulatedRobot::toolContactWrench() const noexcept {
  Vector6d wrench_world = Vector6d::Zero();
  const Eigen::Vector3d tcp_world(data_->xpos[3 * tip_body_], data_->xpos[3 * tip_body_ + 1],
                                  data_->xpos[3 * tip_body_ + 2]);
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& contact = data_->contact[i];
    const bool tool1 = tool_body_[model_->geom_bodyid[contact.geom1]];
    const bool tool2 = tool_body_[model_->geom_bodyid[contact.geom2]];
    if (tool1 == tool2) {
      continue;  // not touching the tool, or the tool touching itself
    }
    mjtNum local[6];
    mj_contactForce(model_.get(), data_.get(), i, local);
    // The contact frame's rows are the normal (pointing from geom1 to geom2) and two tangents;
    // the force is the one geom1 exerts on geom2.
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(contact.frame);
    Eigen::Vector3d force = frame.transpose() * Eigen::Vector3d(local[0], local[1], local[2]);
    if (tool1) {
      force = -force;  // the environment (geom2) pushes back on the tool (geom1)
    }
    const Eigen::Vector3d arm = Eigen::Map<const Eigen::Vector3d>(contact.pos) - tcp_world;
    wrench_world.head<3>() += force;
    wrench_world.tail<3>() += arm.cross(force);
  }
  // Into the base frame.
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> base_rotation(
      data_->xmat + 9 * static_cast<std::ptrdiff_t>(base_body_));
  Vector6d wrench;
  wrench.head<3>() = base_rotation.transpose() * wrench_world.head<3>();
  wrench.tail<3>() = base_rotation.transpose() * wrench_world.tail<3>();
  return wrench;
}

}  // namespace comply::sim
