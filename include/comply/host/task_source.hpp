#pragma once
// A task file as a command source (task::CommandSource): the motion reference along the waypoints
// at the task's command rate, each waypoint's other fields (gains, task frame, feedforward) the
// moment it comes due, and, for a task with a path block, the path stream from its start time on.

#include <memory>
#include <optional>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/host/task_file.hpp"
#include "comply/task/command_source.hpp"
#include "comply/task/path_command.hpp"

namespace comply::host {

/// The reference of a task at one time: pose (or joint position) and its rate.
struct Reference {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vector6d twist = Vector6d::Zero();
  JointVector joint_position;
  JointVector joint_velocity;
};

/// Waypoint targets resolved against the start: absolute positions, orientations carried over;
/// interpolation (slerp) at a constant speed or by minimum jerk, with the matching velocity, or a
/// step.
class Trajectory {
 public:
  Trajectory(const TaskFile& task, const Reference& start);
  [[nodiscard]] Reference at(double t) const;
  [[nodiscard]] double endTime() const { return times_.back(); }

 private:
  [[nodiscard]] Reference target(const Waypoint& waypoint, const Reference& previous) const;

  Reference start_;
  std::vector<Reference> targets_;
  std::vector<double> times_;
  std::vector<Interpolation> interpolation_;
};

/// The period [s] at which a task streams its reference: its command rate, in whole control
/// periods of `period_s`.
double commandPeriodOf(const TaskFile& task, double period_s);

template <typename Command>
class TaskSource final : public task::CommandSource<Command> {
 public:
  /// `seeded`: the command in force right after activation (its pose is where the task starts);
  /// `command_period_s`: how often the motion reference is sent; `period_s`: the control period.
  TaskSource(const TaskFile& task, const Command& seeded, int dof, double period_s);

  std::optional<Command> next(double t_s, const MeasuredPose& measured) override;
  [[nodiscard]] double motionEndTime() const override { return end_of_motion_s_; }

 private:
  const TaskFile& task_;
  int dof_;
  double period_s_;
  double command_period_s_;
  double next_send_s_ = 0.0;
  std::size_t next_waypoint_ = 0;
  Trajectory trajectory_;
  Command base_;
  std::unique_ptr<task::PathCommand> path_;
  double end_of_motion_s_ = 0.0;
};

extern template class TaskSource<JointCommand>;
extern template class TaskSource<CartesianCommand>;

}  // namespace comply::host
