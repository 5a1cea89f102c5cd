#include "comply/pipeline/motion_governor.hpp"

#include <algorithm>
#include <cmath>

namespace comply::pipeline {
namespace {

// Shares of a governed speed (motion_governor.hpp): the law's push must be unwindable before
// kBrakeFrom; past it the stage brakes. The TCP's share starts falling at kTcpFrom.
constexpr double kBrakeFrom = 0.85;
constexpr double kJointFrom = 0.2;
constexpr double kTcpFrom = 0.5;

/// The law's share the TCP allows at speed `speed` of limit `limit` (0: none).
double tcpSpeedShare(double speed, double limit) noexcept {
  if (limit <= 0.0 || speed <= kTcpFrom * limit) {
    return 1.0;
  }
  return std::clamp((kBrakeFrom * limit - speed) / ((kBrakeFrom - kTcpFrom) * limit), 0.0, 1.0);
}

}  // namespace

MotionGovernor::MotionGovernor(const ResolvedController& resolved, bool tcp)
    : parameters_(resolved.parameters), dof_(resolved.dof) {
  const JointVector& inertia = parameters_.joint_inertia;
  // Every bound below divides by or scales with a joint's inertia: a model without one (a massless
  // joint) is not governed rather than governed to a standstill.
  enabled_ =
      parameters_.governor.enabled && inertia.size() == dof_ && (inertia.array() > 0.0).all();
  tcp_ = tcp && enabled_;
  // An admittance's virtual arm is no heavier than the arm without its rotors, for which a brake
  // sized on the rotors' inertia is far past deadbeat; its speed is bounded by the virtual arm
  // itself (output.admittance.velocity_factor, below the brakes' 0.85 x velocity_fraction).
  brake_ = !isAdmittance(parameters_.output.mode);
  if (enabled_) {
    root_inertia_ = inertia.cwiseSqrt();
  }
}

double MotionGovernor::jointShare(const JointState& state, double period_s,
                                  const JointVector& law_torque) const noexcept {
  const JointVector& governed = parameters_.governed_speed;
  const JointVector& inertia = parameters_.joint_inertia;
  const JointVector& rate_limit = parameters_.torque_rate_limit;
  // The other joints' torques reach joint i through the inverse inertia's off-diagonal, at most
  // |tau_j| / sqrt(m_i m_j) of acceleration each (Cauchy-Schwarz on the positive definite inverse,
  // whose diagonal is at most 1 / m): their share of joint i's push, in its worst direction.
  double coupled = 0.0;
  for (int j = 0; j < dof_; ++j) {
    coupled += std::abs(law_torque[j]) / root_inertia_[j];
  }
  double share = 1.0;
  for (int i = 0; i < dof_; ++i) {
    const double velocity = state.velocity[i];
    const double own = velocity > 0.0 ? law_torque[i] : -law_torque[i];
    // A slow joint is left alone: a law holding a contact pushes at rest, and what a push from
    // slow can add is what the margin above kJointFrom is for. A URDF without a velocity limit
    // (0) bounds nothing, as for the stability guard.
    if (!(governed[i] > 0.0) || std::abs(velocity) < kJointFrom * governed[i]) {
      continue;
    }
    const double push = std::max(own, 0.0) + root_inertia_[i] * coupled - std::abs(law_torque[i]);
    if (push <= 0.0) {
      continue;  // the law brakes this joint and nothing else pushes it: never scaled
    }
    const double margin = std::max(kBrakeFrom * governed[i] - std::abs(velocity), 0.0);
    double allowed = inertia[i] * margin / period_s;
    if (std::isfinite(rate_limit[i])) {  // an admittance's virtual arm has no rate limit
      allowed = std::min(allowed, std::sqrt(2.0 * rate_limit[i] * inertia[i] * margin));
    }
    if (push > allowed) {
      share = std::min(share, allowed / push);
    }
  }
  return share;
}

double MotionGovernor::tcpShare(const Vector6d& tcp_twist, double law_power) const noexcept {
  if (law_power <= 0.0) {
    return 1.0;  // the law takes energy out: never scaled
  }
  const GovernorConfig& config = parameters_.governor;
  return std::min(tcpSpeedShare(tcp_twist.head<3>().norm(), config.tcp_speed_m_per_s),
                  tcpSpeedShare(tcp_twist.tail<3>().norm(), config.tcp_angular_speed_rad_per_s));
}

bool MotionGovernor::brakeJoints(const JointState& state, double period_s,
                                 JointVector& torque) const noexcept {
  const JointVector& governed = parameters_.governed_speed;
  const JointVector& inertia = parameters_.joint_inertia;
  bool braked = false;
  for (int i = 0; i < dof_; ++i) {
    const double velocity = state.velocity[i];
    const double excess = std::abs(velocity) - kBrakeFrom * governed[i];
    if (!(governed[i] > 0.0) || !(excess > 0.0)) {
      continue;
    }
    const double brake =
        std::min(inertia[i] / (2.0 * period_s) * excess, parameters_.effort_limit[i]);
    torque[i] -= velocity > 0.0 ? brake : -brake;
    braked = true;
  }
  return braked;
}

bool MotionGovernor::brakeTcp(const Vector6d& tcp_twist, const model::Data& data, double period_s,
                              JointVector& torque) const noexcept {
  Vector6d wrench = Vector6d::Zero();
  const auto brake = [&](int row, double limit, double inertia) noexcept {
    const Eigen::Vector3d velocity = tcp_twist.segment<3>(row);
    const double speed = velocity.norm();
    const double excess = speed - kBrakeFrom * limit;
    if (limit <= 0.0 || inertia <= 0.0 || excess <= 0.0) {
      return false;
    }
    wrench.segment<3>(row) = -(inertia / (2.0 * period_s) * excess / speed) * velocity;
    return true;
  };
  const GovernorConfig& config = parameters_.governor;
  const bool linear = brake(0, config.tcp_speed_m_per_s, parameters_.tcp_mass_kg);
  const bool angular = brake(3, config.tcp_angular_speed_rad_per_s, parameters_.tcp_inertia_kg_m2);
  if (!linear && !angular) {
    return false;
  }
  torque.head(dof_).noalias() += data.jacobian.leftCols(dof_).transpose() * wrench;
  return true;
}

GovernorResult MotionGovernor::apply(const JointState& state, const Vector6d& tcp_twist,
                                     const model::Data& data, double period_s,
                                     JointVector& law_torque, JointVector& torque) const noexcept {
  GovernorResult result;
  if (!enabled_ || !(period_s > 0.0)) {
    return result;
  }
  result.share = jointShare(state, period_s, law_torque);
  if (tcp_) {
    result.share = std::min(result.share, tcpShare(tcp_twist, law_torque.dot(state.velocity)));
  }
  if (result.share < 1.0) {
    torque -= (1.0 - result.share) * law_torque;
    law_torque *= result.share;
  }
  if (brake_) {
    result.braked = brakeJoints(state, period_s, torque);
    if (tcp_) {
      result.braked = brakeTcp(tcp_twist, data, period_s, torque) || result.braked;
    }
  }
  return result;
}

}  // namespace comply::pipeline
