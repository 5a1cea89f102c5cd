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

/// Lower Cholesky factor L of an SPD matrix and L^-1, unblocked: Eigen's LLT plus a triangular
/// inverse cost several times more at 6x6. False when a pivot is not positive (or is NaN).
bool choleskyWithInverse(const Matrix6d& a, Matrix6d& lower, Matrix6d& lower_inverse) noexcept {
  lower.setZero();
  Vector6d reciprocal;
  for (int j = 0; j < 6; ++j) {
    double pivot = a(j, j);
    for (int k = 0; k < j; ++k) {
      pivot -= lower(j, k) * lower(j, k);
    }
    if (!(pivot > 0.0)) {
      return false;
    }
    lower(j, j) = std::sqrt(pivot);
    reciprocal[j] = 1.0 / lower(j, j);
    for (int i = j + 1; i < 6; ++i) {
      double value = a(i, j);
      for (int k = 0; k < j; ++k) {
        value -= lower(i, k) * lower(j, k);
      }
      lower(i, j) = value * reciprocal[j];
    }
  }
  lower_inverse.setZero();
  for (int j = 0; j < 6; ++j) {
    lower_inverse(j, j) = reciprocal[j];
    for (int i = j + 1; i < 6; ++i) {
      double sum = 0.0;
      for (int k = j; k < i; ++k) {
        sum += lower(i, k) * lower_inverse(k, j);
      }
      lower_inverse(i, j) = -sum * reciprocal[i];
    }
  }
  return true;
}

/// 2 sqrt(A) for a symmetric PSD A = diag(a) + E with a small off-diagonal rest E, to second
/// order: sqrt(A) ~ R + X1 + X2 with R = diag(sqrt(a)), R X1 + X1 R = E and R X2 + X2 R = -X1^2
/// (the Frechet derivatives of the square root, Higham, Functions of Matrices, 6.1). Unlike
/// eigenvectors, this needs no gap between eigenvalues.
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
  std::memcpy(&basis, basis_, sizeof(basis));
  const lanes::Matrix symmetric = lanes::product(
      lanes::loadTransposed(lower), lanes::product(lanes::load(stiffness), lanes::load(lower)));
  lanes::Matrix nearly_diagonal;
  last_sweeps_ = lanes::trackEigen(symmetric, basis, nearly_diagonal, kJacobiTolerance);
  std::memcpy(basis_, &basis, sizeof(basis));
  // D = 2 L^-T sqrt(L^T K L) L^-1 with sqrt(L^T K L) = U sqrt(A) U^T.
  const lanes::Matrix modes = lanes::product(lanes::loadTransposed(lower_inverse), basis);
  lanes::store(lanes::product(lanes::product(modes, twiceSquareRoot(nearly_diagonal)),
                              lanes::transpose(modes)),
               damping);
  return true;
}

}  // namespace comply
