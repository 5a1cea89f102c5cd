#pragma once
// The safe state "hold": what goes out in FAULT, a controlled stop (as a stop category 1 does),
// without a reference that may be the cause of the fault:
//
//   stopping   every joint is decelerated within its effort limit: the arm held against gravity
//              (and the payload) and each joint braked by D_i v_i, at most what its effort limit
//              leaves beside gravity. D_i = max(fault_damping_i, m_i / (2 T)) with m_i the joint's
//              lightest inertia over the workspace: half of deadbeat on the lightest inertia,
//              stable on every heavier one. The damping only takes energy out, so the arm comes
//              to rest however the joints couple.
//   at rest    once every joint is slower than kRestSpeed, the pose it stopped at is held by a
//              joint spring (w_n T = 0.1 on the lightest inertia) with the same damping, and the
//              hardware's own hold (brakes) is asked for (Controller::holdRequested).
//
// On a frozen sensor stream the velocity is stale: the arm is held against the gravity of its
// last pose only, and the hardware's hold asked for at once. The gravity is that of the last
// usable state: kept after every successful model update, which a failed one may leave half
// written. The stopping distance per robot is in docs/safety.md. Real-time.

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class SafeHold {
 public:
  /// Below this speed on every joint [rad/s | m/s] the arm is at rest.
  static constexpr double kRestSpeed = 0.01;

  explicit SafeHold(const CycleParameters& parameters, int dof);

  /// Forgets the pose it held: the next FAULT starts with a stop.
  void reset() noexcept;
  /// The gravity (+ payload) at the state `data` was just evaluated at becomes the holding base.
  void keepGravity(const model::Data& data) noexcept;
  /// The stopping or holding torque at `state` (its velocity unused when `frozen`: a stale
  /// velocity would push in a direction the arm may no longer move) into `torque` [N m], for a
  /// cycle of `period_s`.
  void torque(const JointState& state, bool frozen, double period_s, JointVector& torque) noexcept;
  /// The arm came to rest in this FAULT and is held where it stopped.
  [[nodiscard]] bool atRest() const noexcept { return at_rest_; }

 private:
  [[nodiscard]] double damping(int joint, double period_s) const noexcept;

  const CycleParameters& parameters_;
  int dof_ = 0;
  JointVector gravity_;  // at the last usable state: the holding base
  JointVector rest_position_;
  bool at_rest_ = false;
};

}  // namespace comply::pipeline
