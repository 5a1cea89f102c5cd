#include "comply/task/online_path_frame.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>

#include "comply/task/frames.hpp"

namespace comply::task {
namespace {

// Parametrised by chord length, the fitted path's speed |dr/ds| is 1 wherever the window is one
// way along the path; at a reversal the fit folds the way out and the way back and its slope at the
// newest sample passes through zero, so the direction it gives there means nothing.
constexpr double kMinFittedSpeed = 0.5;

}  // namespace

OnlinePathFrame::OnlinePathFrame(const OnlinePathFrameOptions& options,
                                 const Eigen::Matrix3d& initial_frame)
    : options_(options) {
  if (!(options_.sample_spacing_m > 0.0) || options_.window_samples < 3) {
    throw std::invalid_argument(
        "OnlinePathFrame: sample spacing must be > 0 and the window at least 3 samples");
  }
  window_.resize(static_cast<std::size_t>(options_.window_samples));
  reset(initial_frame);
}

void OnlinePathFrame::reset(const Eigen::Matrix3d& initial_frame) {
  initial_frame_ = initial_frame;
  frame_ = initial_frame;
  newest_ = -1;
  count_ = 0;
  tracking_ = false;
  curvature_per_m_ = 0.0;
}

const OnlinePathFrame::Sample& OnlinePathFrame::sample(int age) const noexcept {
  const int size = options_.window_samples;
  return window_[static_cast<std::size_t>((newest_ - age + size) % size)];
}

double OnlinePathFrame::pathLength() const noexcept {
  return count_ > 0 ? sample(0).arc_m : 0.0;
}

double OnlinePathFrame::speed() const noexcept {
  if (count_ < 2) {
    return 0.0;
  }
  const Sample& oldest = sample(count_ - 1);
  const double span_s = sample(0).t_s - oldest.t_s;
  return span_s > 0.0 ? (sample(0).arc_m - oldest.arc_m) / span_s : 0.0;
}

const Eigen::Matrix3d& OnlinePathFrame::update(double t_s, const Eigen::Vector3d& position_m) {
  double arc_m = 0.0;
  if (count_ > 0) {
    const double step_m = (position_m - sample(0).position).norm();
    if (!(step_m >= options_.sample_spacing_m)) {
      return frame_;  // not far enough from the last kept position (or not finite)
    }
    arc_m = sample(0).arc_m + step_m;
  }
  newest_ = (newest_ + 1) % options_.window_samples;
  window_[static_cast<std::size_t>(newest_)] = Sample{t_s, arc_m, position_m};
  count_ = std::min(count_ + 1, options_.window_samples);
  if (count_ == options_.window_samples) {
    estimate();
  }
  return frame_;
}

void OnlinePathFrame::estimate() {
  // r(w) = a + b w + c w^2 with w = (arc - newest arc) / window length in [-1, 0]: the scaled
  // parameter keeps the normal equations well conditioned at any spacing.
  const double length_m = sample(0).arc_m - sample(count_ - 1).arc_m;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d right = Eigen::Matrix3d::Zero();
  for (int age = 0; age < count_; ++age) {
    const Sample& s = sample(age);
    const double w = (s.arc_m - sample(0).arc_m) / length_m;
    const Eigen::Vector3d basis(1.0, w, w * w);
    normal += basis * basis.transpose();
    right += basis * s.position.transpose();
  }
  const Eigen::Matrix3d coefficients = normal.ldlt().solve(right);  // rows a, b, c
  const Eigen::Vector3d velocity = coefficients.row(1).transpose() / length_m;
  const Eigen::Vector3d acceleration =
      2.0 * coefficients.row(2).transpose() / (length_m * length_m);
  if (!(velocity.norm() >= kMinFittedSpeed)) {
    return;  // a reversal inside the window: hold the frame until the window has passed it
  }
  const std::optional<Eigen::Vector3d> previous_normal =
      tracking_ ? std::optional<Eigen::Vector3d>(frame_.col(0)) : std::nullopt;
  const std::optional<Eigen::Matrix3d> frenet = frenetFrame(
      velocity, acceleration, previous_normal, initial_frame_.col(0), options_.min_curvature_per_m);
  if (!frenet) {
    return;
  }
  frame_.col(0) = frenet->col(1);
  frame_.col(1) = frenet->col(2);
  frame_.col(2) = frenet->col(0);
  const double speed = velocity.norm();
  curvature_per_m_ = velocity.cross(acceleration).norm() / (speed * speed * speed);
  tracking_ = true;
}

}  // namespace comply::task
