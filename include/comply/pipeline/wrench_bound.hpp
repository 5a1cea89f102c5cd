#pragma once
// The wrench an arm can exert at a pose: a wrench w at the TCP (base frame, force first) takes the
// joint torques J^T w (J the TCP's geometric Jacobian at that pose), so the arm can exert w when
// every |(J^T w)_i| is within joint i's effort limit. The effort ratio
//   r(w) = max_i |(J^T w)_i| / effort_limit_i
// says by how much w overdraws the most loaded joint (r <= 1: within every limit), and w / r is
// the largest wrench along w's direction the arm exerts at that pose. The bound is the effort
// limits' alone: gravity and the law's own torques draw on the same limits, so it is the most the
// arm could give, not what it gives on top of holding itself. Along a direction the arm's
// structure carries (a singular direction, J^T w = 0) nothing bounds the wrench there; it is bound
// again once the arm leaves that pose.
//
// Used at the intake (force_intake.hpp: a force target or feedforward above it is refused) and by
// the force stage every cycle (what it commands is scaled into it). Real-time: no allocation.

#include "comply/core/capacity.hpp"
#include "comply/core/commands.hpp"

namespace comply::pipeline {

struct EffortRatio {
  double ratio = 0.0;  ///< max_i |(J^T w)_i| / effort_limit_i; 0 for a zero wrench
  int joint = -1;      ///< the joint that sets it (-1: none)
};

/// r(w) at the pose whose TCP Jacobian is `jacobian` (its first `dof` columns), over the joints
/// with a finite positive effort limit.
EffortRatio effortRatio(const Jacobian& jacobian, const Vector6d& wrench,
                        const JointVector& effort_limit, int dof) noexcept;

/// Scales `wrench` (6 numbers, base frame, force first) down along its direction to r = 1 when it
/// is above; returns r before. Real-time.
double boundWrench(const Jacobian& jacobian, double* wrench, const JointVector& effort_limit,
                   int dof) noexcept;

}  // namespace comply::pipeline
