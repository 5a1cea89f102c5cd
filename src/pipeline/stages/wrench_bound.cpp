#include "comply/pipeline/wrench_bound.hpp"

#include <cmath>

namespace comply::pipeline {

EffortRatio effortRatio(const Jacobian& jacobian, const Vector6d& wrench,
                        const JointVector& effort_limit, int dof) noexcept {
  EffortRatio result;
  for (int i = 0; i < dof && i < effort_limit.size(); ++i) {
    const double limit = effort_limit[i];
    if (!(limit > 0.0) || !std::isfinite(limit)) {
      continue;
    }
    const double ratio = std::abs(jacobian.col(i).dot(wrench)) / limit;
    if (ratio > result.ratio) {
      result = {ratio, i};
    }
  }
  return result;
}

double boundWrench(const Jacobian& jacobian, double* wrench, const JointVector& effort_limit,
                   int dof) noexcept {
  Eigen::Map<Vector6d> w(wrench);
  const double ratio = effortRatio(jacobian, w, effort_limit, dof).ratio;
  if (ratio > 1.0) {
    w /= ratio;
  }
  return ratio;
}

}  // namespace comply::pipeline
