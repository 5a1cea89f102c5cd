#pragma once
// Dense kernels of the Cartesian law for a DOF fixed at compile time (6, 7) or not (Eigen::Dynamic,
// up to kMaxDof). Private to the plugin. Hand-written because at these sizes Eigen's LLT, LDLT
// and triangular solvers take general-size paths (blocked kernels, run-time loops over a 12-wide
// capacity) that cost several times the arithmetic.

#include <Eigen/Core>
#include <cmath>

#include "comply/core/capacity.hpp"
#include "comply/plugin/abi.h"

namespace comply::controllers {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Storage for N joints: inline, exactly N when N is fixed, up to kMaxDof otherwise.
template <int N>
struct Sized {
  static constexpr int kCapacity = N == Eigen::Dynamic ? kMaxDof : N;
  using Vector = Eigen::Matrix<double, N, 1, Eigen::ColMajor, kCapacity, 1>;
  using Matrix = Eigen::Matrix<double, N, N, Eigen::ColMajor, kCapacity, kCapacity>;
  using Jacobian = Eigen::Matrix<double, 6, N, Eigen::ColMajor, 6, kCapacity>;
};

/// Lambda^-1 = J M^-1 J^T from M = L D L^T (L unit lower triangular): with Z = J L^-T,
/// Lambda^-1 = Z D^-1 Z^T = sum_j z_j z_j^T / d_j. One factorisation with the forward
/// substitution for Z interleaved, no triangular solve per column of J^T, and no square root:
/// the chain from one column to the next is a single division. The mass matrix is read from the
/// plugin input (column-major, leading dimension COMPLY_MAX_DOF). False when M is not positive
/// definite.
template <int N>
bool inverseCartesianInertia(const double* mass_matrix, const typename Sized<N>::Jacobian& jacobian,
                             Matrix6d& inverse_inertia) noexcept {
  const int n = static_cast<int>(jacobian.cols());
  typename Sized<N>::Matrix lower(n, n);   // unit diagonal, not stored
  typename Sized<N>::Matrix scaled(n, n);  // L_ik d_k
  typename Sized<N>::Jacobian z(6, n);
  typename Sized<N>::Jacobian z_scaled(6, n);  // Z D^-1
  for (int j = 0; j < n; ++j) {
    const double* column = mass_matrix + j * COMPLY_MAX_DOF;
    double pivot = column[j];
    for (int k = 0; k < j; ++k) {
      pivot -= lower(j, k) * scaled(j, k);
    }
    if (!(pivot > 0.0)) {
      return false;
    }
    const double reciprocal = 1.0 / pivot;
    for (int i = j + 1; i < n; ++i) {
      double value = column[i];
      for (int k = 0; k < j; ++k) {
        value -= scaled(i, k) * lower(j, k);
      }
      scaled(i, j) = value;
      lower(i, j) = value * reciprocal;
    }
    // Row j of L is complete: column j of Z from Z L^T = J.
    Vector6d zj = jacobian.col(j);
    for (int k = 0; k < j; ++k) {
      zj -= lower(j, k) * z.col(k);
    }
    z.col(j) = zj;
    z_scaled.col(j) = reciprocal * zj;
  }
  // One product at the end: seven 6x6 rank-one updates in the loop were twice as slow.
  inverse_inertia = z_scaled.lazyProduct(z.transpose());
  return true;
}

/// Solves a x = b for a symmetric positive definite 6x6 `a` by an unblocked L D L^T
/// factorisation (a division, not a square root and a division, between columns). False
/// (x untouched) when a pivot is not positive.
inline bool solvePositiveDefinite(const Matrix6d& a, const Vector6d& b, Vector6d& x) noexcept {
  Matrix6d lower = Matrix6d::Zero();   // unit diagonal, not stored
  Matrix6d scaled = Matrix6d::Zero();  // L_ik d_k
  Vector6d reciprocal;
  for (int j = 0; j < 6; ++j) {
    double pivot = a(j, j);
    for (int k = 0; k < j; ++k) {
      pivot -= lower(j, k) * scaled(j, k);
    }
    if (!(pivot > 0.0)) {
      return false;
    }
    reciprocal[j] = 1.0 / pivot;
    for (int i = j + 1; i < 6; ++i) {
      double value = a(i, j);
      for (int k = 0; k < j; ++k) {
        value -= scaled(i, k) * lower(j, k);
      }
      scaled(i, j) = value;
      lower(i, j) = value * reciprocal[j];
    }
  }
  Vector6d z;
  for (int i = 0; i < 6; ++i) {
    double value = b[i];
    for (int k = 0; k < i; ++k) {
      value -= lower(i, k) * z[k];
    }
    z[i] = value;
  }
  for (int i = 5; i >= 0; --i) {
    double value = z[i] * reciprocal[i];
    for (int k = i + 1; k < 6; ++k) {
      value -= lower(k, i) * x[k];
    }
    x[i] = value;
  }
  return true;
}

}  // namespace comply::controllers
