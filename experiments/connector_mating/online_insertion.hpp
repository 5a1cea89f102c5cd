#pragma once
// The insertion of the online_fsf conditions, after the paper: "the compliance frame was
// initialized in the TCP frame but updated online to the FSF, dynamically aligning the compliant
// directions with the connector geometry. Consequently, the robot advanced along the FSF z-axis
// while retaining compliance in the degrees of freedom required to compensate for misalignment."
//
// The command knows nothing of the socket. Every command: the Frenet-Serret frame of the measured
// TCP path (task::OnlinePathFrame, z the direction of travel; the measured TCP frame until the TCP
// has moved a window's length) is the task frame; the reference is the measured position plus a
// lead along that z. The lead is what the reference was ahead of the arm along z at the last
// command plus the insertion speed times the command period, so along z the reference runs at the
// speed of the other conditions' reference and a stalled arm sees its axial force build up at the
// same rate; across z the reference sits on the arm (nothing pulls it back to a planned line).
// The reference stops advancing after the other conditions' travel (50 mm) and then holds.
//
// The orientation reference either stays the commanded peg-down orientation (the frame moves the
// gains only) or turns the peg's axis onto the frame's z by the shortest rotation (the peg is
// asked to point where it goes): the paper's sentence reads both ways, so both are conditions.

#include <Eigen/Geometry>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/task/online_path_frame.hpp"

namespace comply::experiments::connector_mating {

/// What one command of an online insertion did, for the trace and the README's analysis.
struct OnlineRecord {
  double t_s = 0.0;
  Eigen::Vector3d task_z = Eigen::Vector3d::Zero();  ///< base frame
  double lead_m = 0.0;                               ///< reference ahead of the TCP along z
  bool tracking = false;                             ///< frame from the path (else the TCP's)
};

class OnlineInsertion {
 public:
  /// The estimator's settings, the same for every online condition: a sample every 0.5 mm of TCP
  /// travel, 8 samples (3.5 mm of path) per fit.
  static task::OnlinePathFrameOptions pathFrameOptions();

  OnlineInsertion(double speed_m_per_s, double travel_m, const Eigen::Quaterniond& peg_down,
                  bool orientation_follows_frame);

  /// Sets position, twist, orientation and task frame of `command` at `t_s`; the first call
  /// starts the insertion where the arm is.
  void apply(double t_s, const MeasuredPose& measured, CartesianCommand& command);

  [[nodiscard]] const std::vector<OnlineRecord>& records() const noexcept { return records_; }

 private:
  task::OnlinePathFrame path_frame_;
  double speed_m_per_s_;
  double travel_m_;
  Eigen::Quaterniond peg_down_;
  bool orientation_follows_frame_;
  bool started_ = false;
  double last_t_s_ = 0.0;
  double advanced_m_ = 0.0;
  Eigen::Vector3d reference_ = Eigen::Vector3d::Zero();
  std::vector<OnlineRecord> records_;
};

}  // namespace comply::experiments::connector_mating
