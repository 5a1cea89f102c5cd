#include "comply/task/path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "comply/core/number_text.hpp"

namespace comply::task {

Path::Path(const std::vector<Eigen::Vector3d>& points, double spacing_m, double derivative_step_m)
    : spacing_m_(spacing_m), derivative_step_m_(derivative_step_m) {
  if (points.size() < 2) {
    throw std::invalid_argument("Path needs at least two points");
  }
  if (!(spacing_m > 0.0) || !(derivative_step_m >= spacing_m)) {
    throw std::invalid_argument("Path: spacing must be > 0 and the derivative step >= spacing");
  }
  std::vector<double> arc{0.0};
  for (std::size_t i = 1; i < points.size(); ++i) {
    arc.push_back(arc.back() + (points[i] - points[i - 1]).norm());
  }
  length_ = arc.back();
  if (!(length_ > 0.0) || !std::isfinite(length_)) {
    throw std::invalid_argument("Path has zero or non-finite length");
  }
  const double intervals = std::ceil(length_ / spacing_m_);
  if (intervals >= static_cast<double>(kMaxPathSamples)) {
    const NumberTexts samples = numbersApart(intervals + 1.0, static_cast<double>(kMaxPathSamples));
    const NumberTexts length =
        numbersApart(length_, spacing_m_ * static_cast<double>(kMaxPathSamples - 1));
    char spacing_mm[32];
    std::snprintf(spacing_mm, sizeof spacing_mm, "%.6g", spacing_m_ * 1e3);
    throw std::invalid_argument("Path of " + length.value + " m would need " + samples.value +
                                " samples at " + spacing_mm + " mm spacing, above the limit of " +
                                samples.limit + " (" + length.limit + " m)");
  }
  const auto count = static_cast<std::size_t>(intervals) + 1;
  spacing_m_ = length_ / static_cast<double>(count - 1);
  samples_.reserve(count);
  std::size_t segment = 1;
  for (std::size_t k = 0; k < count; ++k) {
    const double s = std::min(length_, static_cast<double>(k) * spacing_m_);
    while (segment + 1 < arc.size() && arc[segment] < s) {
      ++segment;
    }
    const double span = arc[segment] - arc[segment - 1];
    const double u = span > 0.0 ? (s - arc[segment - 1]) / span : 0.0;
    samples_.push_back(points[segment - 1] + u * (points[segment] - points[segment - 1]));
  }
}

Eigen::Vector3d Path::position(double s) const noexcept {
  const double clamped = std::clamp(s, 0.0, length_);
  const double index = clamped / spacing_m_;
  const auto lower = std::min(static_cast<std::size_t>(index), samples_.size() - 2);
  const double u = index - static_cast<double>(lower);
  return samples_[lower] + u * (samples_[lower + 1] - samples_[lower]);
}

Eigen::Vector3d Path::tangent(double s) const noexcept {
  // Central difference, one-sided within half a step of either end.
  const double h = 0.5 * derivative_step_m_;
  const double a = std::clamp(s - h, 0.0, length_ - 2.0 * h);
  const Eigen::Vector3d difference = position(a + 2.0 * h) - position(a);
  return difference.normalized();
}

Eigen::Vector3d Path::curvatureVector(double s) const noexcept {
  const double h = derivative_step_m_;
  const double centre = std::clamp(s, h, length_ - h);
  return (position(centre + h) - 2.0 * position(centre) + position(centre - h)) / (h * h);
}

}  // namespace comply::task
