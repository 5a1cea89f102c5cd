#include "comply/core/gains.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace comply {

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
  const Eigen::LLT<Matrix6d> factor(inverse_inertia);
  if (factor.info() != Eigen::Success) {
    return false;
  }
  const Matrix6d lower = factor.matrixL();
  const Matrix6d symmetric = lower.transpose() * stiffness * lower;
  Vector6d eigenvalues;
  last_sweeps_ = symmetricEigenJacobi(symmetric, basis_, eigenvalues);
  // Q = L^-T U, then D = Q diag(2 sqrt(k)) Q^T.
  // Column by column: a 6x6 right-hand side would select the blocked (general size) solver.
  Matrix6d q;
  for (int column = 0; column < 6; ++column) {
    q.col(column) = lower.transpose().triangularView<Eigen::Upper>().solve(basis_.col(column));
  }
  damping = q * (2.0 * eigenvalues.cwiseMax(0.0).cwiseSqrt()).asDiagonal() * q.transpose();
  return true;
}

}  // namespace comply
