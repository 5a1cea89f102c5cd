#pragma once
// A Frenet-Serret frame estimated online from measured positions: the frame of the path the TCP
// actually takes, for a compliance frame that follows the motion when the controller does not know
// the geometry that guides it (a connector's axis, a groove, an edge).
//
//   task::OnlinePathFrame path_frame(options, measured_tcp_orientation);  // TCP frame at first
//   every command period: task_frame = path_frame.update(t, measured.tcp_position);
//
// How it estimates: a measured position joins a fixed-size window only once it lies
// `sample_spacing_m` from the last one that did, so the window spans a length of path, not a time
// (at standstill nothing changes; noise well below the spacing never enters). Over the window a
// quadratic is fitted by least squares against chord length; its first and second derivatives at
// the newest sample are the tangent and the curvature vector, from which frenetFrame() builds the
// frame. Evaluated at the newest sample, the fit has no lag on a straight path and at most about a
// spacing's worth on a curve, but it is the fit's noisiest point: with +-20 um of noise per
// coordinate and the default 3.5 mm window the tangent wanders by up to 2.5 deg.
//
// No allocation after construction: the window is sized once.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace comply::task {

struct OnlinePathFrameOptions {
  /// Distance [m] a measured position must lie from the last kept one to be kept.
  double sample_spacing_m = 5e-4;
  /// Positions in the window (>= 3). The frame leaves the initial frame once the window is full,
  /// after (window_samples - 1) * sample_spacing_m of travel.
  int window_samples = 8;
  /// Below this curvature [1/m] the principal normal is undefined (a straight path, or noise) and
  /// is carried over from the last frame (see frenetFrame()). Set it above the curvature the
  /// measurement noise fakes, about noise / window length^2.
  double min_curvature_per_m = 2.0;
};

class OnlinePathFrame {
 public:
  /// Throws std::invalid_argument on a spacing <= 0 or fewer than 3 window samples.
  explicit OnlinePathFrame(const OnlinePathFrameOptions& options = {},
                           const Eigen::Matrix3d& initial_frame = Eigen::Matrix3d::Identity());

  /// Forgets the path: frame() is `initial_frame` (columns x, y, z) until the window fills again.
  void reset(const Eigen::Matrix3d& initial_frame);

  /// Takes the position measured at `t_s` [s] (base frame [m]) and returns frame().
  const Eigen::Matrix3d& update(double t_s, const Eigen::Vector3d& position_m);

  /// Columns x = principal normal N, y = binormal B, z = tangent T (direction of travel): the
  /// Frenet-Serret frame ordered like a tool frame, whose z is the approach axis. The initial frame
  /// until tracking(); held through a reversal of the motion until the window has passed it.
  [[nodiscard]] const Eigen::Matrix3d& frame() const noexcept { return frame_; }
  /// True once the frame comes from the path rather than from the initial frame.
  [[nodiscard]] bool tracking() const noexcept { return tracking_; }
  /// Curvature [1/m] of the fit at the newest sample; 0 until tracking().
  [[nodiscard]] double curvature() const noexcept { return curvature_per_m_; }
  /// Path length [m] covered by the kept samples since the last reset.
  [[nodiscard]] double pathLength() const noexcept;
  /// Mean speed [m/s] along the window (its path length over its time span, which includes any
  /// stop inside it); 0 below 2 samples.
  [[nodiscard]] double speed() const noexcept;

 private:
  struct Sample {
    double t_s = 0.0;
    double arc_m = 0.0;  // path length from the first sample after the reset
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
  };

  [[nodiscard]] const Sample& sample(int age) const noexcept;  // 0: newest
  void estimate();

  OnlinePathFrameOptions options_;
  std::vector<Sample> window_;  // ring buffer, sized once
  int newest_ = -1;
  int count_ = 0;
  Eigen::Matrix3d initial_frame_;
  Eigen::Matrix3d frame_;
  bool tracking_ = false;
  double curvature_per_m_ = 0.0;
};

}  // namespace comply::task
