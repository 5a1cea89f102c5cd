#pragma once
// Gain ramps: rate limits that move the gains in force toward the ones a command asks for, a step
// at a time, so that a step in a command reaches the law as a ramp. Every stiffness, damping and
// damping-ratio entry moves at most at its configured rate (gain_ramps.*), the task frame at most
// at its angular rate. A matrix moves along the straight line to its target, so on the way it is
// a convex combination of two PSD matrices and stays PSD; a diagonal gain moves entry by entry.
// Each function moves `current` in place by at most one step and returns whether it has arrived:
// the stage stops moving gains once every one of them has. Real-time safe.

#include <Eigen/Geometry>

namespace comply::pipeline {

/// Moves `count` entries of `current` toward `target` along the straight line, so that no entry
/// moves more than `max_step`. Arrived, `current` is `target` bit for bit.
bool approach(double* current, const double* target, int count, double max_step) noexcept;

/// Diagonal gains: each entry on its own, at most `max_step` (they stay non-negative).
bool approachEach(double* current, const double* target, int count, double max_step) noexcept;

/// Turns `current` toward `goal` along the shortest arc by at most `max_step_rad`.
bool approachFrame(Eigen::Quaterniond& current, const Eigen::Quaterniond& goal,
                   double max_step_rad) noexcept;

/// `current` moved the fraction `beta` of the way to `target`; all of it lands on `target` exactly.
/// What is left of a step another limit (the energy tank) held back.
void blend(double* current, const double* target, int count, double beta) noexcept;

}  // namespace comply::pipeline
