#include "comply/pipeline/force_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

using Eigen::Map;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// A base-frame 6-vector (linear first) in the task frame `rotation`, and back.
Vector6d toTask(const Matrix3d& rotation, const double* base) noexcept {
  Vector6d task;
  task.head<3>().noalias() = rotation.transpose() * Map<const Vector3d>(base);
  task.tail<3>().noalias() = rotation.transpose() * Map<const Vector3d>(base + 3);
  return task;
}

void toBase(const Matrix3d& rotation, const Vector6d& task, double* base) noexcept {
  Map<Vector3d> linear(base);
  Map<Vector3d> angular(base + 3);
  linear.noalias() = rotation * task.head<3>();
  angular.noalias() = rotation * task.tail<3>();
}

/// The pose error (reference - measured) of `in` at the measured pose, in the task frame `task`.
Vector6d poseError(const Matrix3d& task, const comply_cartesian_command& in,
                   const Vector3d& position, const Eigen::Quaterniond& orientation) noexcept {
  Vector6d error;
  error.head<3>().noalias() = task.transpose() * (Map<const Vector3d>(in.position) - position);
  error.tail<3>().noalias() =
      task.transpose() * orientationError(orientation, schema::fromXyzw(in.orientation));
  return error;
}

/// The reference of `out` = the measured pose plus `error` (task frame), block by block where
/// `error` differs from `unchanged` (the other block keeps the reference as it is, bit for bit).
void writeReference(const Matrix3d& task, const Vector6d& error, const Vector6d& unchanged,
                    const Vector3d& position, const Eigen::Quaterniond& orientation,
                    comply_cartesian_command& out) noexcept {
  if (error.head<3>() != unchanged.head<3>()) {
    Map<Vector3d>(out.position) = position + task * error.head<3>();
  }
  if (error.tail<3>() != unchanged.tail<3>()) {
    schema::toXyzw(quaternionExp(task * error.tail<3>()) * orientation, out.orientation);
  }
}

}  // namespace

void anchorForceAxes(comply_cartesian_command& bus, const Vector3d& position,
                     const Eigen::Quaterniond& orientation) noexcept {
  const Map<const Vector6d> selected(bus.force_axes);
  if ((selected.array() == 0.0).all()) {
    return;
  }
  const Matrix3d task = schema::fromXyzw(bus.task_frame).normalized().toRotationMatrix();
  Vector6d error = poseError(task, bus, position, orientation);
  const Vector6d unchanged = error;
  for (int axis = 0; axis < 6; ++axis) {
    if (selected[axis] != 0.0) {
      error[axis] = 0.0;
    }
  }
  writeReference(task, error, unchanged, position, orientation, bus);
}

void ForceAxes::configure(const ForceControlConfig& config) noexcept {
  config_ = config;
  limit_ << config.contact_force_limit_n, config.contact_torque_limit_n_m;
  limited_ = (limit_.array() > 0.0).any();
  integral_limit_ << Vector3d::Constant(config.integral_limit_n),
      Vector3d::Constant(config.integral_limit_n_m);
  max_speed_ << Vector3d::Constant(config.max_speed_m_per_s),
      Vector3d::Constant(config.max_angular_speed_rad_per_s);
  reset();
}

void ForceAxes::reset() noexcept {
  integral_.setZero();
  pull_back_.setZero();
  force_command_.setZero();
}

bool ForceAxes::acts(const comply_cartesian_command& in) const noexcept {
  return limited_ || (Map<const Vector6d>(in.force_axes).array() != 0.0).any();
}

void ForceAxes::apply(const comply_cartesian_command& in, const model::Data& data,
                      const Vector6d& tcp_twist, const Vector6d* wrench_on_tool, double period_s,
                      comply_cartesian_command& out) noexcept {
  const Map<const Vector6d> selected(in.force_axes);
  out = in;
  const Matrix3d task = schema::fromXyzw(in.task_frame).normalized().toRotationMatrix();

  // Everything in the task frame: the pose error (reference - measured), the command's rates and
  // feedforward, the measured twist and the wrench the TCP exerts (minus the one it receives).
  Vector6d error = poseError(task, in, data.tip_position, data.tip_orientation);
  Vector6d twist = toTask(task, in.twist);
  Vector6d acceleration = toTask(task, in.acceleration);
  Vector6d feedforward = toTask(task, in.wrench_feedforward);
  Vector6d speed;
  speed.head<3>().noalias() = task.transpose() * tcp_twist.head<3>();
  speed.tail<3>().noalias() = task.transpose() * tcp_twist.tail<3>();
  Vector6d exerted = Vector6d::Zero();
  if (wrench_on_tool != nullptr) {
    exerted = -toTask(task, wrench_on_tool->data());
  }
  const bool estimated = wrench_on_tool != nullptr;

  const Vector6d unchanged = error;
  for (int axis = 0; axis < 6; ++axis) {
    if (selected[axis] != 0.0) {
      error[axis] = 0.0;
      twist[axis] = 0.0;
      acceleration[axis] = 0.0;
      pull_back_[axis] = 0.0;
      feedforward[axis] +=
          forceLoop(axis, in.wrench_target[axis], exerted[axis], estimated, speed[axis], period_s);
      if (limit_[axis] > 0.0) {  // the command's own feedforward along the axis included
        feedforward[axis] = std::clamp(feedforward[axis], -limit_[axis], limit_[axis]);
      }
      continue;
    }
    integral_[axis] = 0.0;
    force_command_[axis] = 0.0;
    if (limit_[axis] > 0.0) {
      const double* block = axis < 3 ? in.stiffness_translational : in.stiffness_rotational;
      const double stiffness =
          block[static_cast<std::ptrdiff_t>(axis % 3) * 4];  // the diagonal entry, row-major 3x3
      error[axis] = limitAxis(axis, error[axis], exerted[axis], estimated, stiffness, period_s);
      feedforward[axis] = std::clamp(feedforward[axis], -limit_[axis], limit_[axis]);
    }
  }

  writeReference(task, error, unchanged, data.tip_position, data.tip_orientation, out);
  toBase(task, twist, out.twist);
  toBase(task, acceleration, out.acceleration);
  toBase(task, feedforward, out.wrench_feedforward);
  Map<Vector6d>(out.force_axes).setZero();
}

double ForceAxes::forceLoop(int axis, double target, double exerted, bool estimated, double speed,
                            double period_s) noexcept {
  const double error = estimated ? target - exerted : 0.0;
  const double held = integral_[axis];
  if (config_.integral_gain_per_s > 0.0) {
    const double bound = integral_limit_[axis] / config_.integral_gain_per_s;
    integral_[axis] = std::clamp(held + error * period_s, -bound, bound);
  }
  double push =
      target + config_.proportional_gain * error + config_.integral_gain_per_s * integral_[axis];
  // Moving faster than max_speed in the direction it pushes: no contact holds the arm. The push
  // fades to nothing at twice that speed, and the integral keeps what it held (anti-windup).
  const double pushing_speed = push >= 0.0 ? speed : -speed;
  const double fade = std::clamp(2.0 - pushing_speed / max_speed_[axis], 0.0, 1.0);
  if (fade < 1.0) {
    integral_[axis] = held;
    push = fade * (target + config_.proportional_gain * error + config_.integral_gain_per_s * held);
  }
  if (limit_[axis] > 0.0) {
    push = std::clamp(push, -limit_[axis], limit_[axis]);
  }
  force_command_[axis] = push;
  return push;
}

double ForceAxes::limitAxis(int axis, double error, double exerted, bool estimated,
                            double stiffness, double period_s) noexcept {
  if (!(stiffness > 0.0)) {
    pull_back_[axis] = 0.0;  // no spring to pull back
    return error;
  }
  if (!estimated) {
    // A cycle without a reading: the pull-back holds (letting it go would put the spring's whole
    // force back on the contact at once).
    pull_back_[axis] = std::min(pull_back_[axis], std::abs(error));
    return error >= 0.0 ? error - pull_back_[axis] : error + pull_back_[axis];
  }
  // The force in the direction the spring pushes, above (> 0) or below the limit.
  const double excess = (error >= 0.0 ? exerted : -exerted) - limit_[axis];
  const double rate = std::clamp(2.0 * M_PI * config_.limit_bandwidth_hz * excess / stiffness,
                                 -max_speed_[axis], max_speed_[axis]);
  pull_back_[axis] = std::clamp(pull_back_[axis] + rate * period_s, 0.0, std::abs(error));
  return error >= 0.0 ? error - pull_back_[axis] : error + pull_back_[axis];
}

}  // namespace comply::pipeline
