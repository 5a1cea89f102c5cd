#pragma once
// The command stream of one surface-following run: approach in free space, press onto the start
// of the face, traverse it at constant speed along the nominal contact path pushed into the
// surface (task::PathCommand, Darboux frame), hold at the end.

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "comply/task/command_source.hpp"
#include "comply/task/path_command.hpp"

namespace comply::experiments::surface_following {

/// The normal force every condition aims at: the impedance conditions' spring (50 N/m pushed
/// 100 mm into the face), the force conditions' target [N].
inline constexpr double kNormalForceN = 5.0;

struct SurfaceCondition {
  std::string name;
  bool task_aligned = true;  ///< false: the gains stay in the base frame
  bool displaced = false;    ///< the fixture moved and turned; the command does not know
  /// Force control along the task frame's normal axis (target kNormalForceN) from the press on,
  /// instead of the 50 N/m spring; which wrench estimate it reads.
  bool force = false;
  std::string source = "sensor";  ///< force: sensor | observer
};

class SurfaceStream final : public task::CartesianSource {
 public:
  /// `home_tcp`: where the arm starts; `orientation`: the TCP orientation held throughout;
  /// `fraction`: the share of the face traversed.
  SurfaceStream(const SurfaceCondition& condition, const Eigen::Vector3d& home_tcp,
                const Eigen::Quaterniond& orientation, double speed_m_per_s, double fraction,
                int dof);

  /// Always a command: the stream ignores the measured pose.
  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override;
  [[nodiscard]] double motionEndTime() const override { return traverseEnd(); }

  static double traverseStart();
  [[nodiscard]] double traverseEnd() const;
  [[nodiscard]] double duration() const;  ///< traverse end plus the hold
  [[nodiscard]] double speed() const { return speed_; }

 private:
  SurfaceCondition condition_;
  Eigen::Vector3d home_tcp_;
  int dof_;
  double speed_;
  task::PathCommand stream_;
  Eigen::Vector3d start_tcp_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d approach_tcp_ = Eigen::Vector3d::Zero();
};

}  // namespace comply::experiments::surface_following
