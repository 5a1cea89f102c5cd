#pragma once
// Streams Cartesian commands along a Path: constant speed, stiffness per task axis, critically
// damped (damping ratio against the Cartesian inertia), and the task frame taken from the path
// (Frenet-Serret), from the path on a surface (Darboux) or held fixed.
//
//   task::PathCommand stream(path, options);
//   every command period: wrapper.submit(stream.commandAt(t, dof));

#include <Eigen/Geometry>
#include <functional>
#include <optional>

#include "comply/core/commands.hpp"
#include "comply/task/command_source.hpp"
#include "comply/task/path.hpp"

namespace comply::task {

enum class FrameSource {
  kFixed,    ///< `fixed_task_frame` throughout
  kFrenet,   ///< tangent, principal normal, binormal of the path
  kDarboux,  ///< tangent, surface normal at the point, their cross product
};

struct PathCommandOptions {
  double speed_m_per_s = 0.02;
  double start_time_s = 0.0;  ///< the reference leaves the path's start at this time
  FrameSource frame = FrameSource::kFrenet;
  Eigen::Quaterniond fixed_task_frame = Eigen::Quaterniond::Identity();
  /// kDarboux: unit outward surface normal at a path point [base frame].
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> surface_normal;
  /// Frenet fallback where the path is straight: the normal is chosen closest to this.
  Eigen::Vector3d fallback_normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d stiffness_translational =
      Eigen::Vector3d::Constant(1000.0);  ///< per task axis [N/m]
  Eigen::Vector3d stiffness_rotational =
      Eigen::Vector3d::Constant(50.0);  ///< per task axis [N m/rad]
  double damping_ratio = 1.0;           ///< 1: critically damped on every axis
  /// Reference displaced from the path by this vector in the task frame [m], e.g. into a surface
  /// along its normal so that a compliant axis presses with stiffness x offset.
  Eigen::Vector3d offset_in_task_frame = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< TCP orientation held
};

class PathCommand final : public CartesianSource {
 public:
  PathCommand(Path path, PathCommandOptions options);

  /// CommandSource: commandAt(t, number of measured joints), every call.
  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override {
    return commandAt(t_s, static_cast<int>(measured.position.size()));
  }
  /// When the reference reaches the path's end [s].
  [[nodiscard]] double motionEndTime() const override {
    return options_.start_time_s + path_.length() / options_.speed_m_per_s;
  }

  /// The command at time `t` [s]: before start_time_s the path's start, after the end its end
  /// (zero twist). Sets position, velocity, stiffness, damping and task-frame fields.
  [[nodiscard]] CartesianCommand commandAt(double t, int dof);
  /// The task frame at arc length `s` (columns: task axes in the base frame). Successive calls
  /// within 2 cm of arc length keep the Frenet normal's sign (see frenetFrame()).
  [[nodiscard]] Eigen::Matrix3d taskFrame(double s);
  /// Arc length reached at time `t`.
  [[nodiscard]] double arcLength(double t) const;
  [[nodiscard]] const Path& path() const noexcept { return path_; }

 private:
  Path path_;
  PathCommandOptions options_;
  std::optional<Eigen::Vector3d> previous_normal_;
  std::optional<double> previous_s_;
};

}  // namespace comply::task
