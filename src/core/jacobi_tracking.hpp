#pragma once
// trackSymmetricEigen() on column-lane matrices, for CriticalDampingTracker (which keeps its
// whole computation in that form). Private to comply_core.

#include "lanes6.hpp"

namespace comply::lanes {

/// See trackSymmetricEigen(): `rotated` = basis^T matrix basis after the sweeps.
int trackEigen(const Matrix& matrix, Matrix& basis, Matrix& rotated, double relative_tolerance,
               int max_sweeps = 16) noexcept;

}  // namespace comply::lanes
