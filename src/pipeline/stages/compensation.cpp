#include "comply/pipeline/compensation.hpp"

#include <cmath>

namespace comply::pipeline {

void frictionTorque(const FrictionParameters& friction, const JointVector& dq,
                    JointVector& torque) noexcept {
  const auto n = dq.size();
  switch (friction.model) {
    case FrictionModel::kNone:
      torque.setZero(n);
      return;
    case FrictionModel::kSigmoid:
      torque.resize(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const double phi1 = friction.phi1[i];
        const double phi2 = friction.phi2[i];
        const double phi3 = friction.phi3[i];
        torque[i] =
            phi1 / (1.0 + std::exp(-phi2 * (dq[i] + phi3))) - phi1 / (1.0 + std::exp(-phi2 * phi3));
      }
      return;
    case FrictionModel::kViscousCoulomb:
      torque.resize(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        torque[i] = friction.viscous[i] * dq[i] +
                    friction.coulomb[i] * std::tanh(dq[i] / friction.smoothing_velocity);
      }
      return;
  }
}

void softLimitTorque(const SoftLimitParameters& limits, const JointVector& q, const JointVector& dq,
                     JointVector& torque) noexcept {
  const auto n = q.size();
  torque.setZero(n);
  if (!limits.enabled) {
    return;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const double upper_start = limits.upper[i] - limits.margin[i];
    const double lower_start = limits.lower[i] + limits.margin[i];
    if (q[i] > upper_start) {
      torque[i] = -limits.stiffness[i] * (q[i] - upper_start) - limits.damping[i] * dq[i];
    } else if (q[i] < lower_start) {
      torque[i] = -limits.stiffness[i] * (q[i] - lower_start) - limits.damping[i] * dq[i];
    }
  }
}

}  // namespace comply::pipeline
