#pragma once
// The command stream of one connector-mating trial: a stiff approach to 20 mm above the socket's
// entrance, then the TCP straight down the socket axis to 10 mm past the seat, compliant across
// the axis, with the insertion gains expressed in the trial's compliance frame; or, in the online
// conditions, the TCP along the Frenet-Serret frame of its own measured path (OnlineInsertion).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "comply/task/command_source.hpp"
#include "connector_mating/online_insertion.hpp"

namespace comply::experiments::connector_mating {

/// Where the insertion gains (stiff along z, soft across) are expressed.
enum class ComplianceFrame {
  kCommandedTcp,  ///< the commanded TCP orientation: z along the peg as commanded
  kMeasuredTcp,   ///< the measured TCP, every cycle: z along the peg as it is
  kSocket,        ///< the socket's frame: z along the insertion axis
  /// The Frenet-Serret frame of the measured TCP path, estimated online; the reference advances
  /// along its z from the measured position (OnlineInsertion), blind to the socket.
  kOnlinePathFrame,
};

struct Trial {
  std::string condition;
  ComplianceFrame frame = ComplianceFrame::kCommandedTcp;
  double offset_rad = 0.0;  ///< tilt of the socket's axis from the peg's
  /// kOnlinePathFrame: the orientation reference turns the peg onto the frame's z (else held).
  bool orientation_follows_frame = false;
};

/// The trial of `condition`: tcp_fixed, tcp_measured, task_aligned, online_fsf (orientation held)
/// or online_fsf_oriented (orientation follows the frame); throws std::invalid_argument on
/// anything else.
Trial trialOf(const std::string& condition, double offset_rad);

class MatingStream final : public task::CartesianSource {
 public:
  /// `home_tcp`: where the arm starts; `peg_down`: the TCP orientation held throughout (peg
  /// vertical).
  MatingStream(const Trial& trial, const Eigen::Vector3d& home_tcp,
               const Eigen::Quaterniond& peg_down, double rotational_nm_per_rad, int dof);

  /// Ablation: during the insertion, the posture (nullspace) spring pulls towards the joints at
  /// the insertion's start with `stiffness` (damping 1 N m s/rad as configured) instead of the
  /// controller's 5 N m/rad towards the joints at activation.
  void overrideNullspace(double stiffness_nm_per_rad) {
    nullspace_nm_per_rad_ = stiffness_nm_per_rad;
  }

  /// Always a command. Only kOnlinePathFrame reads the measured pose (kMeasuredTcp leaves the
  /// frame to the plugin).
  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override;
  [[nodiscard]] double motionEndTime() const override;

  static double duration();  ///< motion end plus the hold
  static double insertionStart();
  [[nodiscard]] const Eigen::Vector3d& axis() const { return axis_; }
  /// The insertion's stiff task axis (base frame) in effect at `t_s`, given the TCP orientation
  /// measured then; NaN before the insertion.
  [[nodiscard]] Eigen::Vector3d taskAxis(double t_s, const Eigen::Quaterniond& measured_tcp) const;
  /// kOnlinePathFrame: one record per insertion command; otherwise empty.
  [[nodiscard]] const std::vector<OnlineRecord>& onlineRecords() const;

 private:
  [[nodiscard]] CartesianCommand approach(double t_s, CartesianCommand command) const;
  [[nodiscard]] CartesianCommand insertion(double t_s, CartesianCommand command) const;

  Trial trial_;
  Eigen::Vector3d home_tcp_;
  Eigen::Quaterniond peg_down_;
  double rotational_nm_per_rad_;
  int dof_;
  Eigen::Vector3d axis_;
  Eigen::Vector3d tip_to_tcp_;
  Eigen::Vector3d start_tcp_;
  Eigen::Vector3d end_tcp_;
  std::optional<OnlineInsertion> online_;
  std::optional<double> nullspace_nm_per_rad_;
  JointVector insertion_start_joints_;
};

}  // namespace comply::experiments::connector_mating
