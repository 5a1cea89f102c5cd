#pragma once
// The last stage before the hardware, in this order: first-order low-pass, finite check,
// torque-rate limit (N m/s, scaled by the measured period), effort limit (URDF).

#include <vector>

#include "comply/core/capacity.hpp"

namespace comply::pipeline {

struct ShapingLimits {
  double filter_alpha = 1.0;  ///< tau_f = alpha tau + (1 - alpha) tau_f,prev
  JointVector rate_limit;     ///< N m/s per joint
  JointVector effort_limit;   ///< N m per joint
};

struct ShapingResult {
  bool finite = true;      ///< false: the filtered torque held NaN/inf; output is the previous one
  int rate_limited = 0;    ///< joints clipped by the rate limit this cycle
  int effort_limited = 0;  ///< joints clipped by the effort limit this cycle
};

class TorqueShaper {
 public:
  explicit TorqueShaper(ShapingLimits limits);

  /// Restarts filter and rate limit from `torque` (e.g. the measured effort on activation).
  void reset(const JointVector& torque) noexcept;

  /// Shapes `torque` in place. `filter` false skips the low-pass (the safe state wants the holding
  /// torque now, still rate and effort limited).
  ShapingResult apply(JointVector& torque, double period_s, bool filter = true) noexcept;

  [[nodiscard]] const JointVector& lastOutput() const noexcept { return last_output_; }

 private:
  ShapingLimits limits_;
  JointVector filtered_;
  JointVector last_output_;
};

}  // namespace comply::pipeline
