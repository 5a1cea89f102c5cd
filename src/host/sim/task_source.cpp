#include "comply/host/task_source.hpp"

#include <algorithm>

#include "comply/schema/schema.hpp"

namespace comply::host {
namespace {

Eigen::Map<const Eigen::VectorXd> mapped(const std::vector<double>& values) {
  return {values.data(), static_cast<Eigen::Index>(values.size())};
}

void setMotion(CartesianCommand& command, const Reference& reference) {
  command.position = reference.position;
  command.orientation = reference.orientation;
  command.twist = reference.twist;
}
void setMotion(JointCommand& command, const Reference& reference) {
  command.position = reference.joint_position;
  command.velocity = reference.joint_velocity;
}

Reference startOf(const CartesianCommand& seeded) {
  Reference start;
  start.position = seeded.position;
  start.orientation = seeded.orientation;
  return start;
}
Reference startOf(const JointCommand& seeded) {
  Reference start;
  start.joint_position = seeded.position;
  start.joint_velocity = JointVector::Zero(seeded.position.size());
  return start;
}

}  // namespace

Trajectory::Trajectory(const TaskFile& task, const Reference& start) : start_(start) {
  Reference previous = start;
  for (const Waypoint& waypoint : task.waypoints) {
    Reference next = target(waypoint, previous);
    targets_.push_back(next);
    times_.push_back(waypoint.time_s);
    interpolation_.push_back(waypoint.interpolate);
    previous = next;
  }
}

Reference Trajectory::target(const Waypoint& waypoint, const Reference& previous) const {
  Reference target = previous;
  target.twist.setZero();
  if (start_.joint_position.size() > 0) {
    target.joint_velocity.setZero();
    if (waypoint.position) {
      target.joint_position = mapped(*waypoint.position);
    } else if (waypoint.position_offset) {
      target.joint_position = start_.joint_position + mapped(*waypoint.position_offset);
    }
    return target;
  }
  if (waypoint.position) {
    target.position = mapped(*waypoint.position);
  } else if (waypoint.position_offset) {
    target.position = start_.position + Eigen::Vector3d(mapped(*waypoint.position_offset));
  }
  if (waypoint.orientation) {
    const std::vector<double>& q = *waypoint.orientation;
    target.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
  }
  return target;
}

Reference Trajectory::at(double t) const {
  const auto next =
      static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
  if (next == times_.size()) {
    return targets_.back();
  }
  const Reference& from = next == 0 ? start_ : targets_[next - 1];
  const double t0 = next == 0 ? 0.0 : times_[next - 1];
  const double span = times_[next] - t0;
  if (interpolation_[next] == Interpolation::kStep || span <= 0.0) {
    Reference hold = from;
    hold.twist.setZero();
    if (hold.joint_velocity.size() > 0) {
      hold.joint_velocity.setZero();
    }
    return hold;
  }
  const Reference& to = targets_[next];
  // The share s of the way and its rate ds/dt: constant, or minimum jerk (s = 10 u^3 - 15 u^4 +
  // 6 u^5, at rest with no acceleration at both ends).
  const double u = (t - t0) / span;
  double s = u;
  double rate = 1.0 / span;
  if (interpolation_[next] == Interpolation::kSmooth) {
    s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
    rate = 30.0 * u * u * (1.0 - u) * (1.0 - u) / span;
  }
  Reference out = to;
  if (from.joint_position.size() > 0) {
    out.joint_position = from.joint_position + s * (to.joint_position - from.joint_position);
    out.joint_velocity = rate * (to.joint_position - from.joint_position);
    return out;
  }
  out.position = from.position + s * (to.position - from.position);
  Eigen::Quaterniond goal = to.orientation;
  if (from.orientation.dot(goal) < 0.0) {
    goal.coeffs() = -goal.coeffs();  // shortest way round
  }
  out.orientation = from.orientation.slerp(s, goal);
  out.twist.head<3>() = rate * (to.position - from.position);
  // The slerp's angular velocity (about a fixed axis), in the base frame.
  const Eigen::AngleAxisd delta(goal * from.orientation.conjugate());
  out.twist.tail<3>() = rate * delta.angle() * delta.axis();
  return out;
}

double commandPeriodOf(const TaskFile& task, double period_s) {
  const auto periods = std::llround(1.0 / (task.command_rate_hz * period_s));
  return period_s * static_cast<double>(std::max<long long>(1, periods));
}

template <typename Command>
TaskSource<Command>::TaskSource(const TaskFile& task, const Command& seeded, int dof,
                                double period_s)
    : task_(task),
      dof_(dof),
      period_s_(period_s),
      command_period_s_(commandPeriodOf(task, period_s)),
      trajectory_(task, startOf(seeded)),
      base_(seeded) {
  end_of_motion_s_ = trajectory_.endTime();
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    if (task.path_points) {
      path_ = std::make_unique<task::PathCommand>(task::Path(*task.path_points), task.path_options);
      end_of_motion_s_ = std::max(end_of_motion_s_, path_->motionEndTime());
    }
  }
}

template <typename Command>
std::optional<Command> TaskSource<Command>::next(double t_s, const MeasuredPose& measured) {
  // The motion reference at the command rate, waypoint fields the moment they come due.
  bool send = t_s >= next_send_s_ - 0.5 * period_s_;
  if (send) {
    next_send_s_ += command_period_s_;
  }
  Command command = base_;
  command.fields = CommandField::kPosition | CommandField::kVelocity;
  while (next_waypoint_ < task_.waypoints.size() &&
         task_.waypoints[next_waypoint_].time_s <= t_s + 0.5 * period_s_) {
    const Waypoint& waypoint = task_.waypoints[next_waypoint_];
    const Command& given = std::get<Command>(waypoint.command);  // typed when the file was read
    schema::assign(command, given, waypoint.keys);
    command.fields = command.fields | given.fields;
    ++next_waypoint_;
    send = true;
  }
  if (!send) {
    return std::nullopt;
  }
  base_ = command;  // later commands build on the gains a waypoint set
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    if (path_ && t_s >= task_.path_options.start_time_s) {
      command = *path_->next(t_s, measured);
    } else {
      setMotion(command, trajectory_.at(t_s));
    }
  } else {
    setMotion(command, trajectory_.at(t_s));
  }
  command.stamp_s = t_s;
  return command;
}

template class TaskSource<JointCommand>;
template class TaskSource<CartesianCommand>;

}  // namespace comply::host
