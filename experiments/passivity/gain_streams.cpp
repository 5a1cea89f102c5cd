#include "passivity/gain_streams.hpp"

#include <algorithm>
#include <cmath>

#include "comply/schema/schema.hpp"

namespace comply::experiments::passivity {
namespace {

constexpr double kCompliantNPerM = 100.0;
constexpr double kStiffNPerM = 3000.0;
// Low, so that the pump shows, yet above the negative damping K T / 2 = 1.5 N s/m of a 3000 N/m
// spring sampled at 1 kHz: every gain held on its own leaves the law passive, only the switching
// pumps.
constexpr double kTranslationalDampingNsPerM = 5.0;
// Of the order of critical damping for the wrist's rotational inertia (rotor armature included)
// at the controller's 300 N m/rad: only the translational axes are lightly damped.
constexpr double kRotationalDampingNmsPerRad = 10.0;
constexpr double kQuarterTurnRad = 0.5 * M_PI;

}  // namespace

void copyGains(const CartesianCommand& from, CartesianCommand& to) {
  CartesianCommand gains = from;
  gains.stamp_s = to.stamp_s;
  gains.fields = CommandField::kStiffness | CommandField::kDamping | CommandField::kTaskFrame;
  const CommandField fields = to.fields;
  schema::merge(to, gains);
  to.fields = fields;  // the groups `to` set stay as they were
}

PumpStream::PumpStream(PumpedGain pumped, const Eigen::Vector3d& target,
                       const Eigen::Quaterniond& orientation, const CartesianCommand& controller)
    : pumped_(pumped), target_(target), orientation_(orientation), controller_(controller) {}

CartesianCommand PumpStream::gains(bool returning) const {
  CartesianCommand command = controller_;
  command.damping_mode = DampingMode::kAbsolute;
  command.damping_translational = kTranslationalDampingNsPerM * Eigen::Matrix3d::Identity();
  command.damping_rotational = kRotationalDampingNmsPerRad * Eigen::Matrix3d::Identity();
  if (pumped_ == PumpedGain::kStiffness) {
    command.task_frame = Eigen::Quaterniond::Identity();
    command.stiffness_translational =
        (returning ? kStiffNPerM : kCompliantNPerM) * Eigen::Matrix3d::Identity();
  } else {
    // Task x is the soft axis: along base x (the motion) in the identity frame, along base y once
    // the frame has turned, which puts the stiff task y along base x.
    command.stiffness_translational =
        Eigen::Vector3d(kCompliantNPerM, kStiffNPerM, kStiffNPerM).asDiagonal();
    command.task_frame =
        returning ? Eigen::Quaterniond(Eigen::AngleAxisd(kQuarterTurnRad, Eigen::Vector3d::UnitZ()))
                  : Eigen::Quaterniond::Identity();
  }
  return command;
}

std::optional<CartesianCommand> PumpStream::next(double t_s, const MeasuredPose& measured) {
  bool returning = false;
  if (!first_ && t_s > previous_t_s_) {
    const Eigen::Vector3d velocity =
        (measured.tcp_position - previous_tcp_) / (t_s - previous_t_s_);
    returning = (measured.tcp_position - target_).dot(velocity) < 0.0;
  }
  CartesianCommand command = gains(returning);
  command.stamp_s = t_s;
  command.fields = CommandField::kStiffness | CommandField::kDamping | CommandField::kTaskFrame;
  if (first_) {
    command.fields = command.fields | CommandField::kPosition;
    command.position = target_;
    command.orientation = orientation_;
    first_ = false;
  }
  previous_t_s_ = t_s;
  previous_tcp_ = measured.tcp_position;
  return command;
}

SmoothTaskStream::SmoothTaskStream(const Eigen::Vector3d& start,
                                   const Eigen::Quaterniond& orientation,
                                   const CartesianCommand& controller)
    : start_(start), orientation_(orientation), controller_(controller) {}

CartesianCommand SmoothTaskStream::gains(double t_s) const {
  CartesianCommand command = controller_;
  command.stiffness_translational =
      (t_s < 0.5 * kMotionS ? kStiffnessBefore : kStiffnessAfter) * Eigen::Matrix3d::Identity();
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio = Vector6d::Ones();
  command.task_frame = Eigen::Quaterniond::Identity();
  return command;
}

Eigen::Vector3d SmoothTaskStream::reference(double t_s) const {
  // Half a cosine out and half back: zero velocity at both ends and at the far end.
  const double phase = 2.0 * M_PI * std::clamp(t_s / kMotionS, 0.0, 1.0);
  return start_ + 0.5 * kStrokeM * (1.0 - std::cos(phase)) * Eigen::Vector3d::UnitX();
}

std::optional<CartesianCommand> SmoothTaskStream::next(double t_s,
                                                       const MeasuredPose& /*measured*/) {
  CartesianCommand command = gains(t_s);
  command.stamp_s = t_s;
  command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
                   CommandField::kDamping | CommandField::kTaskFrame;
  command.position = reference(t_s);
  command.orientation = orientation_;
  command.twist.setZero();
  if (t_s < kMotionS) {
    const double phase = 2.0 * M_PI * t_s / kMotionS;
    command.twist.x() = 0.5 * kStrokeM * std::sin(phase) * 2.0 * M_PI / kMotionS;
  }
  return command;
}

}  // namespace comply::experiments::passivity
