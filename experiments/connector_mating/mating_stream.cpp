#include "connector_mating/mating_stream.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

Trial trialOf(const std::string& condition, double offset_rad) {
  Trial trial{condition, ComplianceFrame::kCommandedTcp, offset_rad};
  if (condition == "tcp_measured") {
    trial.frame = ComplianceFrame::kMeasuredTcp;
  } else if (condition == "task_aligned") {
    trial.frame = ComplianceFrame::kSocket;
  } else if (condition == "online_fsf" || condition == "online_fsf_oriented") {
    trial.frame = ComplianceFrame::kOnlinePathFrame;
    trial.orientation_follows_frame = condition == "online_fsf_oriented";
  } else if (condition != "tcp_fixed") {
    throw std::invalid_argument(
        "unknown connector-mating condition '" + condition +
        "' (tcp_fixed, tcp_measured, task_aligned, online_fsf or online_fsf_oriented)");
  }
  return trial;
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
  if (trial.frame == ComplianceFrame::kOnlinePathFrame) {
    // The same speed and travel as the reference of the other conditions.
    const double travel_m = (end_tcp_ - start_tcp_).norm();
    online_.emplace(travel_m / kInsertS, travel_m, peg_down_, trial.orientation_follows_frame);
  }
}

double MatingStream::insertionStart() {
  return kApproachS;
}

Eigen::Vector3d MatingStream::taskAxis(double t_s, const Eigen::Quaterniond& measured_tcp) const {
  if (t_s < kApproachS) {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  switch (trial_.frame) {
    case ComplianceFrame::kCommandedTcp:
      return peg_down_ * Eigen::Vector3d::UnitZ();
    case ComplianceFrame::kMeasuredTcp:
      return measured_tcp * Eigen::Vector3d::UnitZ();
    case ComplianceFrame::kSocket:
      return axis_;
    case ComplianceFrame::kOnlinePathFrame:
      break;
  }
  // The last command sent at or before t_s.
  const std::vector<OnlineRecord>& records = online_->records();
  const auto after = std::upper_bound(records.begin(), records.end(), t_s,
                                      [](double t, const OnlineRecord& r) { return t < r.t_s; });
  return after == records.begin() ? peg_down_ * Eigen::Vector3d::UnitZ() : std::prev(after)->task_z;
}

const std::vector<OnlineRecord>& MatingStream::onlineRecords() const {
  static const std::vector<OnlineRecord> kNone;
  return online_ ? online_->records() : kNone;
}

double MatingStream::motionEndTime() const {
  return kApproachS + kInsertS;
}

double MatingStream::duration() {
  return kApproachS + kInsertS + kHoldS;
}

std::optional<CartesianCommand> MatingStream::next(double t_s, const MeasuredPose& measured) {
  CartesianCommand command = CartesianCommand::zero(dof_);
  command.stamp_s = t_s;
  command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
                   CommandField::kDamping | CommandField::kTaskFrame;
  command.orientation = peg_down_;
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setOnes();
  command.stiffness_rotational = Eigen::Matrix3d::Identity() * rotational_nm_per_rad_;
  if (t_s < kApproachS) {
    return approach(t_s, std::move(command));
  }
  command = insertion(t_s, std::move(command));
  if (nullspace_nm_per_rad_) {
    if (insertion_start_joints_.size() == 0) {
      insertion_start_joints_ = measured.position;
    }
    command.fields = command.fields | CommandField::kNullspace;
    command.nullspace_position = insertion_start_joints_;
    command.nullspace_stiffness = JointVector::Constant(dof_, *nullspace_nm_per_rad_);
    command.nullspace_damping = JointVector::Constant(dof_, 1.0);
  }
  if (online_) {
    online_->apply(t_s, measured, command);
  }
  return command;
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
    case ComplianceFrame::kOnlinePathFrame:
      break;  // OnlineInsertion sets the frame, the position and the orientation
  }
  return command;
}

}  // namespace comply::experiments::connector_mating
