#include "connector_mating/online_insertion.hpp"

#include <algorithm>

namespace comply::experiments::connector_mating {

task::OnlinePathFrameOptions OnlineInsertion::pathFrameOptions() {
  // Chosen before any trial ran, from the geometry alone: 0.5 mm is a fifth of the chamfer's
  // lateral take-up per millimetre of descent, and 3.5 mm of path is short against the 26 mm from
  // the start to the seat; contact chatter (micrometres) stays far below the spacing. The plant
  // measures without noise, so the curvature threshold only matters for the lateral axes, whose
  // gains are equal.
  return {.sample_spacing_m = 5e-4, .window_samples = 8, .min_curvature_per_m = 2.0};
}

OnlineInsertion::OnlineInsertion(double speed_m_per_s, double travel_m,
                                 const Eigen::Quaterniond& peg_down, bool orientation_follows_frame)
    : path_frame_(pathFrameOptions()),
      speed_m_per_s_(speed_m_per_s),
      travel_m_(travel_m),
      peg_down_(peg_down),
      orientation_follows_frame_(orientation_follows_frame) {
  records_.reserve(2048);  // one per command: the insertion and the hold at 100 Hz
}

void OnlineInsertion::apply(double t_s, const MeasuredPose& measured, CartesianCommand& command) {
  if (!started_) {
    path_frame_.reset(measured.tcp_orientation.toRotationMatrix());
    reference_ = measured.tcp_position;
    last_t_s_ = t_s;
    started_ = true;
  }
  const Eigen::Matrix3d& frame = path_frame_.update(t_s, measured.tcp_position);
  const Eigen::Vector3d z = frame.col(2);
  const double step_m = std::min(speed_m_per_s_ * (t_s - last_t_s_), travel_m_ - advanced_m_);
  last_t_s_ = t_s;
  const bool advancing = step_m > 0.0;
  if (advancing) {
    advanced_m_ += step_m;
    const double lead_m = (reference_ - measured.tcp_position).dot(z) + step_m;
    reference_ = measured.tcp_position + lead_m * z;
  }
  command.position = reference_;
  command.twist.head<3>() =
      advancing ? Eigen::Vector3d(speed_m_per_s_ * z) : Eigen::Vector3d::Zero();
  command.task_frame = Eigen::Quaterniond(frame);
  command.orientation =
      orientation_follows_frame_
          ? Eigen::Quaterniond::FromTwoVectors(peg_down_ * Eigen::Vector3d::UnitZ(), z) * peg_down_
          : peg_down_;
  if (records_.size() < records_.capacity()) {
    records_.push_back(
        {t_s, z, (reference_ - measured.tcp_position).dot(z), path_frame_.tracking()});
  }
}

}  // namespace comply::experiments::connector_mating
