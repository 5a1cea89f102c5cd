#include "comply/pipeline/gain_ramps.hpp"

#include <algorithm>
#include <cmath>

namespace comply::pipeline {

bool approach(double* current, const double* target, int count, double max_step) noexcept {
  double largest = 0.0;
  for (int i = 0; i < count; ++i) {
    largest = std::max(largest, std::abs(target[i] - current[i]));
  }
  const double fraction = largest <= max_step ? 1.0 : max_step / largest;
  for (int i = 0; i < count; ++i) {
    current[i] = fraction == 1.0 ? target[i] : current[i] + fraction * (target[i] - current[i]);
  }
  return fraction == 1.0;
}

bool approachEach(double* current, const double* target, int count, double max_step) noexcept {
  bool arrived = true;
  for (int i = 0; i < count; ++i) {
    const double change = target[i] - current[i];
    const bool within = std::abs(change) <= max_step;
    current[i] = within ? target[i] : current[i] + std::copysign(max_step, change);
    arrived = arrived && within;
  }
  return arrived;
}

bool approachFrame(Eigen::Quaterniond& current, const Eigen::Quaterniond& goal,
                   double max_step_rad) noexcept {
  const double angle = current.angularDistance(goal);
  current = angle <= max_step_rad ? goal : current.slerp(max_step_rad / angle, goal);
  return angle <= max_step_rad;
}

void blend(double* current, const double* target, int count, double beta) noexcept {
  for (int i = 0; i < count; ++i) {
    current[i] = beta == 1.0 ? target[i] : current[i] + beta * (target[i] - current[i]);
  }
}

}  // namespace comply::pipeline
