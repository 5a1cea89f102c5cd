#include "comply/pipeline/torque_shaper.hpp"

#include <algorithm>
#include <cmath>

namespace comply::pipeline {

TorqueShaper::TorqueShaper(ShapingLimits limits) : limits_(std::move(limits)) {
  reset(JointVector::Zero(limits_.effort_limit.size()));
}

void TorqueShaper::reset(const JointVector& torque) noexcept {
  filtered_ = torque;
  last_output_ = torque;
}

ShapingResult TorqueShaper::apply(JointVector& torque, double period_s, bool filter) noexcept {
  ShapingResult result;
  const auto n = torque.size();
  if (filter) {
    torque = limits_.filter_alpha * torque + (1.0 - limits_.filter_alpha) * filtered_;
  }
  if (!torque.allFinite()) {
    // Never let a NaN reach the filter state or the hardware: repeat the last output.
    result.finite = false;
    torque = last_output_;
    return result;
  }
  filtered_ = torque;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double max_step = limits_.rate_limit[i] * period_s;
    const double stepped =
        std::clamp(torque[i], last_output_[i] - max_step, last_output_[i] + max_step);
    result.rate_limited += stepped != torque[i];
    const double limited = std::clamp(stepped, -limits_.effort_limit[i], limits_.effort_limit[i]);
    result.effort_limited += limited != stepped;
    torque[i] = limited;
  }
  last_output_ = torque;
  return result;
}

}  // namespace comply::pipeline
