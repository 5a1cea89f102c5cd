#pragma once
// Eigen decomposition of a symmetric 6x6 matrix by Jacobi rotations, warm-started from a previous
// eigenbasis. In a control loop the matrix changes little from one cycle to the next, so in the
// warm basis it is nearly diagonal and one or two sweeps suffice: several times faster than a
// cold tridiagonal QR solve, with no allocation and no exceptions.

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

/// The control-loop variant: brings `matrix` to near-diagonal form in a basis tracked across
/// calls, and stops as soon as every off-diagonal entry satisfies the relative criterion
/// |a_pq| <= relative_tolerance * sqrt(|a_pp a_qq|) (Demmel and Veselic, "Jacobi's method is more
/// accurate than QR", SIAM J. Matrix Anal. Appl. 1992), plus a floor of 1e-15 of the largest
/// diagonal entry for exactly singular matrices. On return `rotated` = basis^T matrix basis,
/// symmetric, and the caller uses its small off-diagonal rest (see CriticalDampingTracker).
/// Rotations run in round-robin order (five rounds of three disjoint pairs, independent of each
/// other, so their latencies overlap) and skip pairs that already meet the criterion.
/// `basis` must be orthonormal to about 1e-8 on entry (a previous result, or the identity); it is
/// kept orthonormal by one Newton-Schulz step per call. Returns the sweeps that rotated.
int trackSymmetricEigen(const Matrix6d& matrix, Matrix6d& basis, Matrix6d& rotated,
                        double relative_tolerance, int max_sweeps = 16) noexcept;

}  // namespace comply
