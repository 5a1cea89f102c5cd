#pragma once
// The command stream of one connector-mating trial: a stiff approach to 20 mm above the socket's
// entrance, then the TCP straight down the socket axis to 10 mm past the seat, compliant across
// the axis, with the insertion gains expressed in the trial's compliance frame.

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "comply/task/command_source.hpp"

namespace comply::experiments::connector_mating {

/// Where the insertion gains (stiff along z, soft across) are expressed.
enum class ComplianceFrame {
  kCommandedTcp,  ///< the commanded TCP orientation: z along the peg as commanded
  kMeasuredTcp,   ///< the measured TCP, every cycle: z along the peg as it is
  kSocket,        ///< the socket's frame: z along the insertion axis
};

/// tcp_fixed, tcp_measured or task_aligned; throws std::invalid_argument on anything else.
ComplianceFrame complianceFrameOf(const std::string& condition);

struct Trial {
  std::string condition;
  ComplianceFrame frame = ComplianceFrame::kCommandedTcp;
  double offset_rad = 0.0;  ///< tilt of the socket's axis from the peg's
};

class MatingStream final : public task::CartesianSource {
 public:
  /// `home_tcp`: where the arm starts; `peg_down`: the TCP orientation held throughout (peg
  /// vertical).
  MatingStream(const Trial& trial, const Eigen::Vector3d& home_tcp,
               const Eigen::Quaterniond& peg_down, double rotational_nm_per_rad, int dof);

  /// Always a command: the stream ignores the measured pose (kMeasuredTcp leaves the frame to
  /// the plugin).
  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override;
  [[nodiscard]] double motionEndTime() const override;

  static double duration();  ///< motion end plus the hold
  [[nodiscard]] const Eigen::Vector3d& axis() const { return axis_; }

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
};

}  // namespace comply::experiments::connector_mating
