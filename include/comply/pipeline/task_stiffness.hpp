#pragma once
// The task-space gains a Cartesian stiffness change moves, both stiffness blocks and the task
// frame, and the energy their springs hold at an error: 1/2 e^T K_base e with K_base = R K R^T
// (K in the task frame R). The gain stage ramps them (gain_ramps.hpp); the energy tank prices a
// change as the difference of two such energies (energy_tank.hpp). Real-time safe.

#include <Eigen/Geometry>
#include <algorithm>

#include "comply/schema/schema.hpp"

namespace comply::pipeline {

/// The task frame of a bus, normalised; an all-zero quaternion is the identity, as the laws
/// read it.
inline Eigen::Quaterniond frameOf(const double* xyzw) noexcept {
  const Eigen::Quaterniond frame = schema::fromXyzw(xyzw);
  const double norm = frame.norm();
  return norm > 1e-12 ? Eigen::Quaterniond(frame.coeffs() / norm) : Eigen::Quaterniond::Identity();
}

/// 1/2 e^T R K R^T e for a row-major task-frame K: the spring energy at error `error` [J].
inline double springEnergy(const double* stiffness, const Eigen::Quaterniond& frame,
                           const Eigen::Vector3d& error) noexcept {
  const Eigen::Vector3d in_task = frame.conjugate() * error;
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> k(stiffness);
  return 0.5 * in_task.dot(k * in_task);
}

/// Both stiffness blocks (row-major, in the task frame) and the frame.
struct TaskStiffness {
  double translational[9];  ///< [N/m]
  double rotational[9];     ///< [N m/rad]
  Eigen::Quaterniond frame;

  /// The spring energy at these errors (position [m], rotation vector [rad]) [J].
  [[nodiscard]] double energy(const Eigen::Vector3d& position_error,
                              const Eigen::Vector3d& orientation_error) const noexcept {
    return springEnergy(translational, frame, position_error) +
           springEnergy(rotational, frame, orientation_error);
  }
  /// The gains a fraction `beta` of the way from `from` to `to`.
  static TaskStiffness between(const TaskStiffness& from, const TaskStiffness& to,
                               double beta) noexcept {
    TaskStiffness result;
    for (int i = 0; i < 9; ++i) {
      result.translational[i] =
          from.translational[i] + beta * (to.translational[i] - from.translational[i]);
      result.rotational[i] = from.rotational[i] + beta * (to.rotational[i] - from.rotational[i]);
    }
    result.frame = from.frame.slerp(beta, to.frame);
    return result;
  }
  /// A Cartesian bus's.
  static TaskStiffness of(const comply_cartesian_command& bus) noexcept {
    TaskStiffness result;
    std::copy_n(bus.stiffness_translational, 9, result.translational);
    std::copy_n(bus.stiffness_rotational, 9, result.rotational);
    result.frame = frameOf(bus.task_frame);
    return result;
  }
};

}  // namespace comply::pipeline
