#include "comply/pipeline/contact_reflex.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace comply::pipeline {
namespace {

/// sqrt(sum_i (v_i / t_i)^2): above 1 outside the ellipsoid of semi-axes `t` (all above 0).
double ellipsoidRatio(const Eigen::Vector3d& value, const Eigen::Vector3d& semi_axes) noexcept {
  return value.cwiseQuotient(semi_axes).norm();
}

/// `value` (base frame) against the ellipsoid of semi-axes `semi_axes` along the axes of `task`.
/// A sphere is the same in every frame: no rotation then, the common case (the file's thresholds,
/// or a command that raised none).
double taskRatio(const Eigen::Vector3d& value, const Eigen::Quaterniond& task,
                 const Eigen::Vector3d& semi_axes) noexcept {
  if ((semi_axes.array() == semi_axes.x()).all()) {
    return value.norm() / semi_axes.x();
  }
  return ellipsoidRatio(task.conjugate() * value, semi_axes);
}

}  // namespace

void ContactReflex::reset() noexcept {
  above_s_ = -1.0;
  without_s_ = 0.0;
  tripped_ = false;
  tripped_wrench_task_.setZero();
  retreat_direction_.setZero();
  retreat_start_.setZero();
  detail_[0] = '\0';
}

ReflexThresholds ContactReflex::thresholds(const double* force,
                                           const double* torque) const noexcept {
  ReflexThresholds result;
  for (int i = 0; i < 3; ++i) {
    result.force_n[i] = force[i] > 0.0 ? force[i] : config_.force_n;
    result.torque_nm[i] = torque[i] > 0.0 ? torque[i] : config_.torque_nm;
  }
  return result;
}

ContactReflex::Check ContactReflex::check(const Vector6d* wrench, const Eigen::Quaterniond& task,
                                          const ReflexThresholds& thresholds,
                                          double period_s) noexcept {
  in_force_ = thresholds;
  if (wrench == nullptr || !wrench->allFinite()) {
    // Neither a count nor its end: the contact may still be there.
    without_s_ += period_s;
    if (without_s_ + 1e-9 < kNoEstimateTimeoutS) {
      return Check::kArmed;
    }
    std::snprintf(detail_, sizeof(detail_),
                  "no contact wrench for %.3g s: the reflex needs the momentum observer "
                  "(observer.enabled) or the hardware's wrist force/torque reading",
                  without_s_);
    return Check::kNoEstimate;
  }
  without_s_ = 0.0;
  const double force_ratio = taskRatio(wrench->head<3>(), task, thresholds.force_n);
  const double torque_ratio = taskRatio(wrench->tail<3>(), task, thresholds.torque_nm);
  if (!(force_ratio > 1.0) && !(torque_ratio > 1.0)) {
    above_s_ = -1.0;
    return Check::kArmed;
  }
  // The first sample above starts the count at 0: the wrench has been above for above_s_.
  above_s_ = above_s_ < 0.0 ? 0.0 : above_s_ + period_s;
  if (above_s_ + 1e-9 < config_.debounce_s) {
    return Check::kArmed;
  }
  tripped_ = true;
  Vector6d task_wrench;
  task_wrench << task.conjugate() * wrench->head<3>(), task.conjugate() * wrench->tail<3>();
  tripped_wrench_task_ = task_wrench;
  // Back off along the environment's push; a trip on the torque alone gives no direction.
  const double force = wrench->head<3>().norm();
  retreat_direction_ = force_ratio > 1.0 && force > 0.0 ? Eigen::Vector3d(wrench->head<3>() / force)
                                                        : Eigen::Vector3d::Zero();
  describeTrip(task_wrench, thresholds, force_ratio, torque_ratio);
  return Check::kTripped;
}

void ContactReflex::describeTrip(const Vector6d& task_wrench, const ReflexThresholds& thresholds,
                                 double force_ratio, double torque_ratio) noexcept {
  const bool by_force = force_ratio >= torque_ratio;
  const Eigen::Vector3d value = by_force ? task_wrench.head<3>() : task_wrench.tail<3>();
  const Eigen::Vector3d& limit = by_force ? thresholds.force_n : thresholds.torque_nm;
  const char* unit = by_force ? "N" : "N m";
  std::snprintf(detail_, sizeof(detail_),
                "contact %s (%.3g, %.3g, %.3g) %s in the task frame is %.3g times its thresholds "
                "(%.3g, %.3g, %.3g) %s (reflex.%s, or the command's %s) for %.3g s",
                by_force ? "force" : "torque", value.x(), value.y(), value.z(), unit,
                std::max(force_ratio, torque_ratio), limit.x(), limit.y(), limit.z(), unit,
                by_force ? "force_n" : "torque_nm", by_force ? "reflex_force" : "reflex_torque",
                std::max(above_s_, 0.0));
}

void ContactReflex::startRetreat(const Eigen::Vector3d& start) noexcept {
  retreat_start_ = start;
}

void ContactReflex::retreat(double elapsed_s, Eigen::Vector3d& position,
                            Eigen::Vector3d& velocity) const noexcept {
  const double speed = config_.retreat_speed_m_per_s;
  const double travelled = std::clamp(speed * elapsed_s, 0.0, config_.retreat_m);
  position = retreat_start_ + travelled * retreat_direction_;
  const bool moving = travelled < config_.retreat_m;
  velocity = moving ? Eigen::Vector3d(speed * retreat_direction_) : Eigen::Vector3d::Zero();
}

}  // namespace comply::pipeline
