#pragma once
// trackSymmetricEigen() on column-lane matrices, for CriticalDampingTracker (which keeps its
// whole computation in that form). Private to comply_core.

#include "lanes6.hpp"

namespace comply::lanes {

/// See trackSymmetricEigen(): `rotated` = basis^T matrix basis after the sweeps. With
/// `reorthonormalise` false the Newton-Schulz step is skipped: a caller that applies it every
/// few calls keeps the basis orthonormal to rounding (each call departs by ~1e-16 at most).
int trackEigen(const Matrix& matrix, Matrix& basis, Matrix& rotated, double relative_tolerance,
               bool reorthonormalise, int max_sweeps = 16) noexcept;

}  // namespace comply::lanes
