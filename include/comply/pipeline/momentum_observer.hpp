#pragma once
// The generalized-momentum observer (De Luca and Mattone 2005; survey: Haddadin, De Luca and
// Albu-Schaeffer, T-RO 2017): with the arm's dynamics M(q) ddq + C(q, dq) dq + g(q) = tau +
// tau_ext, the residual
//
//   r = K_O ( M(q) dq - p0 - integral( tau + C^T(q, dq) dq - g(q) + r ) dt )
//
// follows the external joint torque as a first-order filter of bandwidth K_O (dr/dt = K_O
// (tau_ext - r)), from joint positions and velocities alone: no acceleration. C^T dq comes from
// dM/dt = C + C^T as dM/dt dq - C dq, dM/dt from the mass matrices of two cycles. The wrench at the
// TCP is the damped least-squares solution of J^T F = r.
//
// Runs in the cycle's measure stage when observer.enabled: no allocation, no lock, no throw. The
// residual and the wrench are updated every cycle: every live host's state sample reads the
// wrench after each cycle, and the reflex and the force stage within it, so solving it once in
// the cycle is what a host pays anyway (and what the bench's observer row times).

#include "comply/core/capacity.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/option_table.hpp"

namespace comply::pipeline {

/// observer.* in the controller file.
struct ObserverConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_OBSERVER_OPTIONS)
};

class MomentumObserver {
 public:
  /// `rotor_inertia`: the part of the model's M(q) diagonal that `tau` does not act on (the
  /// rotors, when tau is a link-side joint-torque sensor's reading, observer.measured_torque:
  /// the sensor sits after them); empty or 0: tau is the drives' own (M(q) as it is).
  void configure(const ObserverConfig& config, int dof,
                 const JointVector& rotor_inertia = JointVector()) noexcept;
  [[nodiscard]] bool enabled() const noexcept { return config_.enabled; }
  /// The next update() starts afresh: p0 from its state, the integral and r at zero.
  void reset() noexcept { started_ = false; }

  /// One cycle: this cycle's velocities and model data (mass matrix, Coriolis, gravity,
  /// Jacobian), `tau` the joint torque that acted over the period that ended [N m | N].
  void update(const JointVector& velocity, const JointVector& tau, const model::Data& data,
              double period_s) noexcept;

  /// The external joint torque estimate r [N m | N]; zero until two updates.
  [[nodiscard]] const JointVector& jointTorque() const noexcept { return residual_; }
  /// The external wrench on the tool at the TCP, base frame, force first [N, N m], from the last
  /// update's residual and Jacobian; zero until two updates.
  [[nodiscard]] const Vector6d& wrench() const noexcept { return wrench_; }

 private:
  ObserverConfig config_;
  int dof_ = 0;
  bool started_ = false;
  JointVector initial_momentum_;  // p0
  JointVector momentum_;          // M dq of this cycle (less the rotors' on a link-side tau)
  JointVector rotor_inertia_;     // the diagonal left out of M
  JointVector integral_;
  JointVector residual_;
  JointMatrix previous_mass_;
  Vector6d wrench_ = Vector6d::Zero();
};

}  // namespace comply::pipeline
