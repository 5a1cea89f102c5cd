#include "connector_mating/mating_stream.hpp"

#include <algorithm>
#include <stdexcept>

#include "connector_mating/peg_and_socket.hpp"

namespace comply::experiments::connector_mating {
namespace {

constexpr double kApproachS = 3.0;  // stiff, ends at rest above the entrance
constexpr double kInsertS = 4.0;
constexpr double kHoldS = 1.5;
constexpr double kStartAbove = 0.02;  // tip above the entrance along the axis
constexpr double kPastSeat = 0.01;    // the reference ends this far beyond the seat
constexpr double kLateralNPerM = 50.0;
constexpr double kAxialNPerM = 1000.0;

}  // namespace

ComplianceFrame complianceFrameOf(const std::string& condition) {
  if (condition == "tcp_fixed") {
    return ComplianceFrame::kCommandedTcp;
  }
  if (condition == "tcp_measured") {
    return ComplianceFrame::kMeasuredTcp;
  }
  if (condition == "task_aligned") {
    return ComplianceFrame::kSocket;
  }
  throw std::invalid_argument("unknown connector-mating condition '" + condition +
                              "' (tcp_fixed, tcp_measured or task_aligned)");
}

MatingStream::MatingStream(const Trial& trial, const Eigen::Vector3d& home_tcp,
                           const Eigen::Quaterniond& peg_down, double rotational_nm_per_rad,
                           int dof)
    : trial_(trial),
      home_tcp_(home_tcp),
      peg_down_(peg_down),
      rotational_nm_per_rad_(rotational_nm_per_rad),
      dof_(dof) {
  axis_ = socketAxis(trial.offset_rad);
  // TCP = tip - R (0, 0, kPegTip); the commanded orientation keeps the peg vertical.
  tip_to_tcp_ = -(peg_down_ * Eigen::Vector3d(0.0, 0.0, kPegTip));
  start_tcp_ = socketEntrance() - kStartAbove * axis_ + tip_to_tcp_;
  end_tcp_ = socketEntrance() + (kHoleDepth + kPastSeat) * axis_ + tip_to_tcp_;
}

double MatingStream::motionEndTime() const {
  return kApproachS + kInsertS;
}

double MatingStream::duration() {
  return kApproachS + kInsertS + kHoldS;
}

std::optional<CartesianCommand> MatingStream::next(double t_s, const MeasuredPose& /*measured*/) {
  CartesianCommand command = CartesianCommand::zero(dof_);
  command.stamp_s = t_s;
  command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
                   CommandField::kDamping | CommandField::kTaskFrame;
  command.orientation = peg_down_;
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setOnes();
  command.stiffness_rotational = Eigen::Matrix3d::Identity() * rotational_nm_per_rad_;
  return t_s < kApproachS ? approach(t_s, std::move(command)) : insertion(t_s, std::move(command));
}

CartesianCommand MatingStream::approach(double t_s, CartesianCommand command) const {
  // Comes to rest a second before the insertion starts.
  const double s = std::min(1.0, t_s / (kApproachS - 1.0));
  command.position = home_tcp_ + s * (start_tcp_ - home_tcp_);
  if (s < 1.0) {
    command.twist.head<3>() = (start_tcp_ - home_tcp_) / (kApproachS - 1.0);
  }
  command.stiffness_translational = Eigen::Matrix3d::Identity() * 3000.0;
  command.stiffness_rotational = Eigen::Matrix3d::Identity() * 100.0;
  return command;
}

CartesianCommand MatingStream::insertion(double t_s, CartesianCommand command) const {
  const double s = std::min(1.0, (t_s - kApproachS) / kInsertS);
  command.position = start_tcp_ + s * (end_tcp_ - start_tcp_);
  if (s < 1.0) {
    command.twist.head<3>() = (end_tcp_ - start_tcp_) / kInsertS;
  }
  command.stiffness_translational =
      Eigen::Vector3d(kLateralNPerM, kLateralNPerM, kAxialNPerM).asDiagonal();
  switch (trial_.frame) {
    case ComplianceFrame::kCommandedTcp:
      command.task_frame = peg_down_;
      break;
    case ComplianceFrame::kMeasuredTcp:
      command.task_frame = Eigen::Quaterniond::Identity();  // relative to the measured TCP
      break;
    case ComplianceFrame::kSocket:
      command.task_frame = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis_);
      break;
  }
  return command;
}

}  // namespace comply::experiments::connector_mating
