#pragma once
// Joint-space terms the wrapper adds to the law's torque. Pure functions of the state: real-time
// safe, each checked against its formula in tests.

#include "comply/core/capacity.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

/// Friction torque the motors must add to overcome joint friction at velocity dq.
/// sigmoid (Gaz et al. 2019): phi1 / (1 + exp(-phi2 (dq + phi3))) - phi1 / (1 + exp(-phi2 phi3));
/// viscous_coulomb: viscous dq + coulomb tanh(dq / smoothing_velocity) (smooth through zero).
void frictionTorque(const FrictionParameters& friction, const JointVector& dq,
                    JointVector& torque) noexcept;

/// Soft joint limits: a spring-damper that engages `margin` before each URDF limit,
///   q > upper - margin:  tau = -k (q - (upper - margin)) - d dq
///   q < lower + margin:  tau = -k (q - (lower + margin)) - d dq
/// and zero in between.
/// `limits` carries the URDF limits (lower, upper) with the margins and gains.
void softLimitTorque(const SoftLimitParameters& limits, const JointVector& q, const JointVector& dq,
                     JointVector& torque) noexcept;

}  // namespace comply::pipeline
