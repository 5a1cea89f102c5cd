#include "comply/task/path_command.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "comply/task/frames.hpp"

namespace comply::task {
namespace {

constexpr double kContinuityRangeM = 0.02;

}  // namespace

PathCommand::PathCommand(Path path, PathCommandOptions options)
    : path_(std::move(path)), options_(std::move(options)) {
  if (!(options_.speed_m_per_s > 0.0)) {
    throw std::invalid_argument("PathCommand: speed must be > 0");
  }
  if (options_.frame == FrameSource::kDarboux && !options_.surface_normal) {
    throw std::invalid_argument("PathCommand: the Darboux frame needs a surface normal");
  }
  if ((options_.stiffness_translational.array() < 0.0).any() ||
      (options_.stiffness_rotational.array() < 0.0).any() || !(options_.damping_ratio >= 0.0)) {
    throw std::invalid_argument("PathCommand: stiffness and damping ratio must be >= 0");
  }
}

double PathCommand::arcLength(double t) const {
  return std::clamp((t - options_.start_time_s) * options_.speed_m_per_s, 0.0, path_.length());
}

Eigen::Matrix3d PathCommand::taskFrame(double s) {
  // The previous normal carries the frame's sign through inflections while streaming; after a
  // jump along the path it says nothing about here.
  if (previous_s_ && std::abs(s - *previous_s_) > kContinuityRangeM) {
    previous_normal_.reset();
  }
  previous_s_ = s;
  std::optional<Eigen::Matrix3d> frame;
  switch (options_.frame) {
    case FrameSource::kFixed:
      return options_.fixed_task_frame.toRotationMatrix();
    case FrameSource::kFrenet:
      frame = frenetFrame(path_.tangent(s), path_.curvatureVector(s), previous_normal_,
                          options_.fallback_normal);
      break;
    case FrameSource::kDarboux: {
      const Eigen::Vector3d point = path_.position(s);
      frame = darbouxFrame(path_.tangent(s), options_.surface_normal(point));
      break;
    }
  }
  if (!frame) {
    // A tangent along the surface normal: keep the last frame rather than send garbage.
    frame = previous_normal_ ? frenetFrame(path_.tangent(s), Eigen::Vector3d::Zero(),
                                           previous_normal_, options_.fallback_normal)
                             : std::nullopt;
    if (!frame) {
      throw std::runtime_error("PathCommand: no task frame at arc length " + std::to_string(s));
    }
  }
  previous_normal_ = frame->col(1);
  return *frame;
}

CartesianCommand PathCommand::commandAt(double t, int dof) {
  CartesianCommand command = CartesianCommand::zero(dof);
  command.stamp_s = t;
  command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
                   CommandField::kDamping | CommandField::kTaskFrame;
  const double s = arcLength(t);
  const Eigen::Matrix3d frame = taskFrame(s);
  command.position = path_.position(s) + frame * options_.offset_in_task_frame;
  command.orientation = options_.orientation;
  const bool moving = t > options_.start_time_s && s < path_.length();
  command.twist.head<3>() =
      moving ? Eigen::Vector3d(options_.speed_m_per_s * path_.tangent(s)) : Eigen::Vector3d::Zero();
  command.task_frame = Eigen::Quaterniond(frame);
  command.stiffness_translational = options_.stiffness_translational.asDiagonal();
  command.stiffness_rotational = options_.stiffness_rotational.asDiagonal();
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setConstant(options_.damping_ratio);
  return command;
}

}  // namespace comply::task
