#include "comply/core/gains.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "jacobi_tracking.hpp"

namespace comply {
namespace {

// Stopping criterion of the tracking Jacobi solver. The square root below is exact to second
// order in the off-diagonal rest, so its error is of the order of the cube of this, relative
// (~1e-12), below the 1e-10 the tracker promises and reached with one sweep per cycle on a
// smooth trajectory at 1 kHz (two or three after a jump).
constexpr double kJacobiTolerance = 1e-4;

/// Lower Cholesky factor F of an SPD matrix and F^-1, as F = L D^1/2 from a = L D L^T (L unit
/// lower triangular): the chain from one column to the next is one division, and the six square
/// roots are independent of each other; L^-1 needs no division at all. Eigen's LLT plus a
/// triangular inverse cost several times more at 6x6. False when a pivot is not positive (or is
/// NaN).
bool choleskyWithInverse(const Matrix6d& a, Matrix6d& lower, Matrix6d& lower_inverse) noexcept {
  Matrix6d unit = Matrix6d::Identity();
  Matrix6d scaled = Matrix6d::Zero();  // L_ik d_k
  Vector6d pivots;
  for (int j = 0; j < 6; ++j) {
    double pivot = a(j, j);
    for (int k = 0; k < j; ++k) {
      pivot -= unit(j, k) * scaled(j, k);
    }
    if (!(pivot > 0.0)) {
      return false;
    }
    pivots[j] = pivot;
    const double reciprocal = 1.0 / pivot;
    for (int i = j + 1; i < 6; ++i) {
      double value = a(i, j);
      for (int k = 0; k < j; ++k) {
        value -= scaled(i, k) * unit(j, k);
      }
      scaled(i, j) = value;
      unit(i, j) = value * reciprocal;
    }
  }
  Matrix6d unit_inverse = Matrix6d::Identity();
  for (int j = 0; j < 6; ++j) {
    for (int i = j + 1; i < 6; ++i) {
      double sum = unit(i, j);
      for (int k = j + 1; k < i; ++k) {
        sum += unit(i, k) * unit_inverse(k, j);
      }
      unit_inverse(i, j) = -sum;
    }
  }
  const Vector6d root = pivots.cwiseSqrt();
  lower = unit * root.asDiagonal();
  lower_inverse = root.cwiseInverse().asDiagonal() * unit_inverse;
  return true;
}

/// 2 sqrt(A) for a symmetric PSD A = diag(a) + E with a small off-diagonal rest E, to second
/// order: sqrt(A) ~ R + X1 + X2 with R = diag(sqrt(a)), R X1 + X1 R = E and R X2 + X2 R = -X1^2
/// (the Frechet derivatives of the square root, Higham, Functions of Matrices, 6.1). Unlike
/// eigenvectors, this needs no gap between eigenvalues.
/// The warm start: the last basis turned once more by the rotation between the last two. On a
/// smooth trajectory the eigenvectors turn by nearly the same small rotation every cycle, so this
/// leaves an error of second order in it: for the FR3's spread of modes (a factor 7000 between
/// the largest and smallest K Lambda^-1 eigenvalue) the relative off-diagonal rest of the plain
/// warm start, ~1e-1, drops to ~1e-3, which saves a sweep per cycle. After a jump (a new K, the
/// first calls) the step is large and is not repeated.
lanes::Matrix extrapolatedBasis(const lanes::Matrix& previous, const lanes::Matrix& last) noexcept {
  const lanes::Matrix step = lanes::product(lanes::transpose(previous), last);
  for (int i = 0; i < 6; ++i) {
    if (!(step.col[i][i] > 0.99)) {
      return last;
    }
  }
  return lanes::product(last, step);
}

lanes::Matrix twiceSquareRoot(const lanes::Matrix& a) noexcept {
  lanes::Lanes root = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 6; ++i) {
    root[i] = std::sqrt(std::max(a.col[i][i], 0.0));
  }
  lanes::Matrix inverse_sum;  // 1 / (r_i + r_j); 0 for two zero roots (then |a_ij| <= 0 for PSD)
  lanes::Matrix first;
  for (int j = 0; j < 6; ++j) {
    const lanes::Lanes sum = root + root[j];
    inverse_sum.col[j] = sum > 0.0 ? 1.0 / sum : 0.0;
    lanes::Lanes off_diagonal = a.col[j];
    off_diagonal[j] = 0.0;
    first.col[j] = off_diagonal * inverse_sum.col[j];
  }
  const lanes::Matrix first_squared = lanes::product(first, first);
  lanes::Matrix result;
  for (int j = 0; j < 6; ++j) {
    lanes::Lanes column = first.col[j] - first_squared.col[j] * inverse_sum.col[j];
    column[j] += root[j];
    result.col[j] = 2.0 * column;
  }
  return result;
}

}  // namespace

bool isSymmetricPsd(const Eigen::Matrix3d& m, double symmetry_tolerance, double psd_tolerance) {
  if (!m.allFinite()) {
    return false;
  }
  const double scale = std::max(1.0, m.cwiseAbs().maxCoeff());
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > symmetry_tolerance * scale) {
    return false;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (m + m.transpose()),
                                                             Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().minCoeff() >= -psd_tolerance * scale;
}

Eigen::Matrix3d dampingFromStiffness(const Eigen::Matrix3d& stiffness, double damping_ratio,
                                     double mass) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(stiffness);
  const Eigen::Vector3d root = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return 2.0 * damping_ratio * std::sqrt(mass) * eigen.eigenvectors() * root.asDiagonal() *
         eigen.eigenvectors().transpose();
}

Matrix6d criticalDamping(const Matrix6d& stiffness, const Matrix6d& inertia) {
  // Generalised problem K v = k Lambda v with V^T Lambda V = I, hence Q = V^-T = Lambda V.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> eigen(stiffness, inertia);
  const Matrix6d q = inertia * eigen.eigenvectors();
  const Eigen::Matrix<double, 6, 1> root = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return q * (2.0 * root).asDiagonal() * q.transpose();
}

CriticalDampingTracker::CriticalDampingTracker() noexcept {
  for (int c = 0; c < 6; ++c) {
    for (int r = 0; r < 8; ++r) {
      basis_[c][r] = r == c ? 1.0 : 0.0;
      previous_basis_[c][r] = basis_[c][r];
    }
  }
}

bool CriticalDampingTracker::compute(const Matrix6d& stiffness, const Matrix6d& inverse_inertia,
                                     Matrix6d& damping) noexcept {
  Matrix6d lower;
  Matrix6d lower_inverse;
  if (!choleskyWithInverse(inverse_inertia, lower, lower_inverse)) {
    return false;
  }
  lanes::Matrix basis;
  lanes::Matrix previous;
  std::memcpy(&basis, basis_, sizeof(basis));
  std::memcpy(&previous, previous_basis_, sizeof(previous));
  std::memcpy(previous_basis_, basis_, sizeof(basis));
  basis = extrapolatedBasis(previous, basis);
  const lanes::Matrix symmetric = lanes::product(
      lanes::loadTransposed(lower), lanes::product(lanes::load(stiffness), lanes::load(lower)));
  lanes::Matrix nearly_diagonal;
  // Newton-Schulz every call: the extrapolation multiplies the departure from orthonormality
  // by about 2.4 per call (U_k+1 = U_k U_k-1^T U_k), so skipping it even for a few calls let
  // the error grow to 1e-9 in 20 calls (measured).
  last_sweeps_ = lanes::trackEigen(symmetric, basis, nearly_diagonal, kJacobiTolerance, true);
  std::memcpy(basis_, &basis, sizeof(basis));
  // D = 2 L^-T sqrt(L^T K L) L^-1 with sqrt(L^T K L) = U sqrt(A) U^T.
  const lanes::Matrix modes = lanes::product(lanes::loadTransposed(lower_inverse), basis);
  lanes::store(lanes::product(lanes::product(modes, twiceSquareRoot(nearly_diagonal)),
                              lanes::transpose(modes)),
               damping);
  return true;
}

}  // namespace comply
