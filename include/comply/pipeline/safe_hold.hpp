#pragma once
// The safe state "hold": what goes out in FAULT. The arm is held against gravity (and the payload)
// and every joint is damped, so it comes to rest where it is, without a reference that may be the
// cause of the fault. Its gravity is that of the last usable state: kept after every successful
// model update, which a failed one may leave half-written. Real-time.

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class SafeHold {
 public:
  explicit SafeHold(const CycleParameters& parameters, int dof);

  /// The gravity (+ payload) at the state `data` was just evaluated at becomes the holding base.
  void keepGravity(const model::Data& data) noexcept;
  /// The holding torque at `state` (its velocity unused when `frozen`: a stale velocity would
  /// push in a direction the arm may no longer move) into `torque` [N m].
  void torque(const JointState& state, bool frozen, JointVector& torque) const noexcept;

 private:
  const CycleParameters& parameters_;
  int dof_ = 0;
  JointVector gravity_;  // at the last usable state: the holding base
};

}  // namespace comply::pipeline
