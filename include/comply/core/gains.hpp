#pragma once
// Checks and helpers for stiffness and damping matrices (3x3 blocks expressed in a task frame).

#include <Eigen/Core>

#include "comply/core/symmetric_eigen.hpp"

namespace comply {

/// True when m is symmetric (to `symmetry_tolerance` relative to its largest entry) and its
/// smallest eigenvalue is >= -psd_tolerance * max(1, largest |entry|).
bool isSymmetricPsd(const Eigen::Matrix3d& m, double symmetry_tolerance = 1e-9,
                    double psd_tolerance = 1e-9);

/// Critically damped damping for stiffness K acting on a unit (or `mass`) inertia:
/// D = 2 zeta sqrt(mass) K^(1/2), the matrix square root taken on K's principal axes.
/// K must be symmetric PSD. zeta = 1 is critical damping.
Eigen::Matrix3d dampingFromStiffness(const Eigen::Matrix3d& stiffness, double damping_ratio = 1.0,
                                     double mass = 1.0);

/// Critical damping for a 6x6 stiffness K acting on a full Cartesian inertia Lambda (both
/// symmetric, Lambda positive definite) by double diagonalisation (Albu-Schaeffer et al., ICRA
/// 2003): with Lambda = Q Q^T and K = Q diag(k) Q^T, D = Q diag(2 sqrt(k)) Q^T. Per-axis damping
/// ratios are applied by the caller as S D S with S = sqrt(zeta) in the stiffness frame, which is
/// zeta D for equal ratios. Fixed-size eigen solver: no allocation, usable every cycle.
Matrix6d criticalDamping(const Matrix6d& stiffness, const Matrix6d& inertia);

/// criticalDamping() for a control loop. It takes the inverse inertia Lambda^-1 = J M^-1 J^T,
/// which the caller has (so Lambda itself is never formed), and keeps the eigenbasis between
/// calls to warm-start a Jacobi solver: with Lambda^-1 = L L^T and L^T K L = U diag(k) U^T,
/// D = 2 L^-T U diag(sqrt(k)) U^T L^-1, the same D as criticalDamping(K, Lambda) (it is twice
/// the matrix geometric mean of K and Lambda). The solver stops at a relative off-diagonal rest
/// of 1e-6 and the square root takes that rest to first order, so D stays within ~1e-10 relative
/// of the exact result with one sweep per cycle.
class CriticalDampingTracker {
 public:
  CriticalDampingTracker() noexcept;
  /// Writes D into `damping`; false (damping untouched) when inverse_inertia is not positive
  /// definite.
  bool compute(const Matrix6d& stiffness, const Matrix6d& inverse_inertia,
               Matrix6d& damping) noexcept;
  /// Sweeps of the last solve: 1-2 while the inputs change smoothly.
  [[nodiscard]] int lastSweeps() const noexcept { return last_sweeps_; }

 private:
  // The eigenbases of the last two calls as six columns of eight lanes (the solver's layout, see
  // src/core/lanes6.hpp), so that no cycle converts them.
  alignas(64) double basis_[6][8];
  alignas(64) double previous_basis_[6][8];
  int last_sweeps_ = 0;
};

}  // namespace comply
