#pragma once
// Eigen decomposition of a symmetric 6x6 matrix by cyclic Jacobi rotations, warm-started from a
// previous eigenbasis. In a control loop the matrix changes little from one cycle to the next,
// so in the warm basis it is nearly diagonal and one or two sweeps reach machine precision:
// several times faster than a cold tridiagonal QR solve, with no allocation and no exceptions.

#include <Eigen/Core>

namespace comply {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Decomposes symmetric `matrix` = basis diag(eigenvalues) basis^T. On entry `basis` is the
/// starting guess (any orthonormal matrix, e.g. the identity or the last result); it is
/// re-orthonormalised first, so rounding cannot accumulate over many warm starts. Returns the
/// number of sweeps used; stops when the off-diagonal part is below 1e-15 of the matrix norm or
/// after `max_sweeps`. Eigenvalues are not sorted.
int symmetricEigenJacobi(const Matrix6d& matrix, Matrix6d& basis, Vector6d& eigenvalues,
                         int max_sweeps = 16) noexcept;

}  // namespace comply
