#pragma once
// A geometric path in the base frame, parametrised by arc length, with the derivatives the
// compliance frames need.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace comply::task {

/// Most samples a path may hold (24 MB): 500 m at the default spacing, far beyond any arm's reach,
/// so a typo such as a point 30 km away is refused instead of exhausting memory.
inline constexpr std::size_t kMaxPathSamples = 1'000'000;

class Path {
 public:
  /// The polyline through `points` [m] (at least two, consecutive points distinct), resampled
  /// every `spacing_m` of arc length. Give points dense enough to describe the curve; derivatives
  /// are central differences over `derivative_step_m` (several spacings), which smooths the
  /// polyline's corners. Throws std::invalid_argument on fewer than two points, a zero length or
  /// more than kMaxPathSamples samples.
  explicit Path(const std::vector<Eigen::Vector3d>& points, double spacing_m = 5e-4,
                double derivative_step_m = 5e-3);

  [[nodiscard]] double length() const noexcept { return length_; }
  /// Point at arc length `s` [m], clamped to [0, length()].
  [[nodiscard]] Eigen::Vector3d position(double s) const noexcept;
  /// dr/ds, a unit vector along the direction of travel.
  [[nodiscard]] Eigen::Vector3d tangent(double s) const noexcept;
  /// d2r/ds2: towards the centre of curvature, with norm the curvature [1/m].
  [[nodiscard]] Eigen::Vector3d curvatureVector(double s) const noexcept;

 private:
  std::vector<Eigen::Vector3d> samples_;  // uniform in arc length
  double spacing_m_;
  double derivative_step_m_;
  double length_ = 0.0;
};

}  // namespace comply::task
