#pragma once
// Stage "govern": no accepted command drives a joint past governor.velocity_fraction of its URDF
// speed, or the TCP past its speeds, whatever the law, its gains and the output mode. The
// stability guard detects an overspeed; this stage prevents one, so the guard's FAULT is the last
// line, not the first.
//
// Method. The law's torque is scaled by one share s in [0, 1], its direction kept (as
// effort_saturation: scale does), so that for every joint i moving faster than 0.2 w_i the law's
// push on it, p_i, stays within what can still be taken back in time:
//
//   p_i <= min( sqrt(2 rho_i m_i margin_i),  m_i margin_i / T ),   margin_i = 0.85 w_i - |v_i|
//
//   p_i = s ( max(sign(v_i) tau_i, 0) + sum_{j != i} |tau_j| sqrt(m_i / m_j) )
//
// w_i the governed speed (velocity_fraction x URDF limit), m_i the joint's lightest inertia over
// the workspace (the others free to move, the rotor inertia included: parameters.joint_inertia),
// rho_i its torque-rate limit, T the period and tau the law's torque. The sum is what the other
// joints' torques can add to joint i's acceleration through the inverse inertia's off-diagonal
// (at most |tau_j| / sqrt(m_i m_j) each, Cauchy-Schwarz on a positive definite matrix whose
// diagonal is at most 1 / m), in its worst direction. The first bound is the push the rate limit
// can unwind before the joint reaches 0.85 w_i (p^2 / (2 rho m) of speed gained while the torque
// ramps down); the second the push that would reach it within one period. A joint past 0.85 w_i is
// braked, -D_i (|v_i| - 0.85 w_i) with D_i = m_i / (2 T) (half of deadbeat on the lightest
// inertia: stable on every heavier one), within its effort limit; the 15 % between 0.85 w_i and
// w_i is the margin for what the model leaves out (Coriolis and centrifugal torques, the lag of
// a rate-limited torque). The law's braking is never scaled, and a joint slower than 0.2 w_i is
// left alone: a law holding a contact pushes at rest.
//
// The TCP (Cartesian laws; governor.tcp_speed_m_per_s, tcp_angular_speed_rad_per_s): while the
// law adds power (tau_law . dq > 0), its share falls linearly from 1 at half a TCP speed limit to 0
// at 0.85 of it; past 0.85 of it the TCP is braked through J^T with the lightest apparent mass
// (inertia) at the TCP over 2 T as the damping.
//
// In the admittance modes the law drives a virtual arm whose speed is bounded by its own
// velocity_factor; there the stage scales but does not brake.
//
// Normal tracking is untouched: while no joint passes 0.2 w_i with more push than the bounds allow
// and the TCP stays below half its limits, s = 1 exactly and the torque is the law's, bit for bit.
//
// Real-time: allocates nothing, takes no lock, never throws.

#include <cstdint>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

/// What the stage did this cycle.
struct GovernorResult {
  double share = 1.0;   ///< of the law's torque let through
  bool braked = false;  ///< a joint or the TCP past 0.85 of its speed was braked
  [[nodiscard]] bool acted() const noexcept { return share < 1.0 || braked; }
};

class MotionGovernor {
 public:
  /// `tcp`: the TCP is governed (a Cartesian law, whose cycle computes the Jacobian).
  MotionGovernor(const ResolvedController& resolved, bool tcp);

  [[nodiscard]] bool enabled() const noexcept { return enabled_; }
  /// Governs `torque` (compensation + law) at `state`: the law's share of it, `law_torque`, is
  /// scaled in both (so later stages see the governed law), and braking is added to `torque`.
  /// When the TCP is governed, `tcp_twist` is this state's J dq and `data` holds its Jacobian.
  GovernorResult apply(const JointState& state, const Vector6d& tcp_twist, const model::Data& data,
                       double period_s, JointVector& law_torque,
                       JointVector& torque) const noexcept;

  /// The speed each joint is governed to [rad/s | m/s] (velocity_fraction x URDF).
  [[nodiscard]] const JointVector& governedSpeed() const noexcept {
    return parameters_.governed_speed;
  }

 private:
  [[nodiscard]] double jointShare(const JointState& state, double period_s,
                                  const JointVector& law_torque) const noexcept;
  [[nodiscard]] double tcpShare(const Vector6d& tcp_twist, double law_power) const noexcept;
  bool brakeJoints(const JointState& state, double period_s, JointVector& torque) const noexcept;
  bool brakeTcp(const Vector6d& tcp_twist, const model::Data& data, double period_s,
                JointVector& torque) const noexcept;

  // w_i (governed_speed), m_i (joint_inertia), rho_i (torque_rate_limit), the effort limits and
  // the TCP's speeds and lightest inertias are the resolved parameters'.
  const CycleParameters& parameters_;
  bool enabled_ = false;
  bool tcp_ = false;
  bool brake_ = true;  // off in admittance (the constructor says why)
  int dof_ = 0;
  JointVector root_inertia_;  // sqrt(m_i), once
};

}  // namespace comply::pipeline
