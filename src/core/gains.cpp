#include "comply/core/gains.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace comply {
namespace {

// Stopping criterion of the tracking Jacobi solver. The first-order square root below leaves an
// error of the order of the square of the off-diagonal rest, relative: ~1e-12 for 1e-6, below the
// 1e-10 the law promises and without a further sweep (measured: one sweep per cycle on a smooth
// trajectory at 1 kHz, two after a jump).
constexpr double kJacobiTolerance = 1e-6;

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

/// 2 sqrt(A) for a symmetric PSD A = diag(a) + E with a small off-diagonal rest E, to first order:
/// sqrt(A) ~ diag(r) + C with r = sqrt(a) and r_i C_ij + C_ij r_j = E_ij (the Frechet derivative
/// of the square root, Higham, Functions of Matrices, 6.1). Unlike eigenvectors, this needs no
/// gap between eigenvalues, and its error is second order in E.
Matrix6d twiceSquareRoot(const Matrix6d& a) noexcept {
  Vector6d root;
  for (int i = 0; i < 6; ++i) {
    root[i] = std::sqrt(std::max(a(i, i), 0.0));
  }
  Matrix6d result;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 6; ++i) {
      const double sum = root[i] + root[j];
      // A PSD matrix has |a_ij| <= sqrt(a_ii a_jj): two zero roots mean a zero entry.
      result(i, j) = i == j ? 2.0 * root[i] : (sum > 0.0 ? 2.0 * a(i, j) / sum : 0.0);
    }
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

bool CriticalDampingTracker::compute(const Matrix6d& stiffness, const Matrix6d& inverse_inertia,
                                     Matrix6d& damping) noexcept {
  Matrix6d lower;
  Matrix6d lower_inverse;
  if (!choleskyWithInverse(inverse_inertia, lower, lower_inverse)) {
    return false;
  }
  const Matrix6d symmetric = lower.transpose() * stiffness * lower;
  Matrix6d nearly_diagonal;
  last_sweeps_ = trackSymmetricEigen(symmetric, basis_, nearly_diagonal, kJacobiTolerance);
  // D = 2 L^-T sqrt(L^T K L) L^-1 with sqrt(L^T K L) = U sqrt(A) U^T.
  const Matrix6d modes = lower_inverse.transpose() * basis_;
  damping = modes * twiceSquareRoot(nearly_diagonal) * modes.transpose();
  return true;
}

}  // namespace comply
