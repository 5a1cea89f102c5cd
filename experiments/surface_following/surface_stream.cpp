#include "surface_following/surface_stream.hpp"

#include <algorithm>
#include <vector>

#include "comply/task/frames.hpp"
#include "surface_following/fixture.hpp"

namespace comply::experiments::surface_following {
namespace {

constexpr double kPressDepth = 0.10;  // reference into the surface: 5 N at 50 N/m
constexpr double kApproachClearance = 0.03;
constexpr double kApproachS = 2.5;
constexpr double kContactS = 2.0;
constexpr double kHoldS = 1.0;
constexpr double kCompliantNPerM = 50.0;
constexpr double kStiffNPerM = 1000.0;

task::Path tcpPath(double fraction) {
  std::vector<Eigen::Vector3d> points = nominalTipPoints(fraction);
  for (Eigen::Vector3d& point : points) {
    point.z() += kProbeLength;
  }
  return task::Path(points);
}

/// `press_depth_m`: how far the reference lies inside the face along its normal.
task::PathCommandOptions streamOptions(const Eigen::Quaterniond& orientation, double speed,
                                       double press_depth_m) {
  task::PathCommandOptions options;
  options.speed_m_per_s = speed;
  options.start_time_s = SurfaceStream::traverseStart();
  options.frame = task::FrameSource::kDarboux;
  // The controller's idea of the fixture: always the nominal one.
  options.surface_normal = [](const Eigen::Vector3d& point) { return outwardNormal(point.x()); };
  options.stiffness_translational = Eigen::Vector3d(kStiffNPerM, kCompliantNPerM, kStiffNPerM);
  options.stiffness_rotational = Eigen::Vector3d::Constant(100.0);
  options.offset_in_task_frame = Eigen::Vector3d(0.0, -press_depth_m, 0.0);
  options.orientation = orientation;
  return options;
}

}  // namespace

SurfaceStream::SurfaceStream(const SurfaceCondition& condition, const Eigen::Vector3d& home_tcp,
                             const Eigen::Quaterniond& orientation, double speed_m_per_s,
                             double fraction, int dof)
    : condition_(condition),
      home_tcp_(home_tcp),
      dof_(dof),
      speed_(speed_m_per_s),
      // Under force control the reference stays on the contact path: a reference pushed into the
      // face along the nominal normal would leak into the tangent wherever the probe's normal
      // differs from the reference's, and hold the probe back on the slope.
      stream_(tcpPath(fraction),
              streamOptions(orientation, speed_m_per_s, condition.force ? 0.0 : kPressDepth)) {
  start_tcp_ = stream_.commandAt(traverseStart(), dof).position;
  approach_tcp_ = stream_.path().position(0.0) + kApproachClearance * outwardNormal(kPathStartX);
}

double SurfaceStream::traverseStart() {
  return kApproachS + kContactS;
}

double SurfaceStream::traverseEnd() const {
  return traverseStart() + stream_.path().length() / speed();
}

double SurfaceStream::duration() const {
  return traverseEnd() + kHoldS;
}

std::optional<CartesianCommand> SurfaceStream::next(double t_s, const MeasuredPose& measured) {
  CartesianCommand command = stream_.commandAt(std::max(t_s, traverseStart()), dof_);
  command.stamp_s = t_s;
  if (t_s < kApproachS) {
    // Free space: stiff in every direction, gains in the base frame.
    const double s = t_s / kApproachS;
    command.position = home_tcp_ + s * (approach_tcp_ - home_tcp_);
    command.twist.head<3>() = (approach_tcp_ - home_tcp_) / kApproachS;
    command.task_frame = Eigen::Quaterniond::Identity();
    command.stiffness_translational = Eigen::Vector3d::Constant(kStiffNPerM).asDiagonal();
    return command;
  }
  if (t_s < traverseStart()) {
    const double s = (t_s - kApproachS) / kContactS;
    command.position = approach_tcp_ + s * (start_tcp_ - approach_tcp_);
    command.twist.head<3>() = (start_tcp_ - approach_tcp_) / kContactS;
  }
  if (!condition_.task_aligned) {
    command.task_frame = Eigen::Quaterniond::Identity();  // 50 N/m stays along base y
  }
  if (condition_.force) {
    // The normal (task y, out of the face) is a force axis: the probe presses into the face,
    // along -y. Its stiffness then only sets the damping along it (ratio mode). The frame turns
    // with the face where the probe touches it (which lags the reference by millimetres on a
    // face whose normal turns by up to 0.15 rad per 8 mm), so that the axis pushes along the
    // normal there.
    if (measured.valid) {
      const Eigen::Vector3d tip =
          measured.tcp_position + measured.tcp_orientation * Eigen::Vector3d(0, 0, kProbeLength);
      const Eigen::Vector3d normal = outwardNormal(tip.x());
      const Eigen::Vector3d tangent(normal.y(), -normal.x(), 0.0);  // along +x
      if (const auto frame = task::darbouxFrame(tangent, normal)) {
        command.task_frame = Eigen::Quaterniond(*frame);
      }
    }
    command.fields = command.fields | CommandField::kForce;
    command.force_axes[1] = 1.0;
    command.wrench_target[1] = -kNormalForceN;
    command.stiffness_translational(1, 1) = kStiffNPerM;
  }
  return command;
}

}  // namespace comply::experiments::surface_following
