// The momentum observer's discrete update (see momentum_observer.hpp).

#include "comply/pipeline/momentum_observer.hpp"

#include <Eigen/Cholesky>

namespace comply::pipeline {
namespace {

/// x with A x = b for a symmetric positive definite 6x6 A: LDL^T without pivoting (stable for a
/// positive definite matrix), written out because Eigen's blocked factorisation of so small a
/// matrix costs the cycle more than the arithmetic does. Reads A's lower triangle.
Vector6d solvePositiveDefinite(const Eigen::Matrix<double, 6, 6>& a, const Vector6d& b) noexcept {
  Eigen::Matrix<double, 6, 6> l = Eigen::Matrix<double, 6, 6>::Identity();
  Vector6d d;
  for (int j = 0; j < 6; ++j) {
    double dj = a(j, j);
    for (int k = 0; k < j; ++k) {
      dj -= l(j, k) * l(j, k) * d[k];
    }
    d[j] = dj;
    for (int i = j + 1; i < 6; ++i) {
      double lij = a(i, j);
      for (int k = 0; k < j; ++k) {
        lij -= l(i, k) * l(j, k) * d[k];
      }
      l(i, j) = lij / dj;
    }
  }
  Vector6d x = b;
  for (int i = 1; i < 6; ++i) {  // L y = b
    for (int k = 0; k < i; ++k) {
      x[i] -= l(i, k) * x[k];
    }
  }
  x.array() /= d.array();         // D z = y
  for (int i = 4; i >= 0; --i) {  // L^T x = z
    for (int k = i + 1; k < 6; ++k) {
      x[i] -= l(k, i) * x[k];
    }
  }
  return x;
}

}  // namespace

void MomentumObserver::configure(const ObserverConfig& config, int dof) noexcept {
  config_ = config;
  dof_ = dof;
  initial_momentum_.setZero(dof);
  momentum_.setZero(dof);
  integral_.setZero(dof);
  residual_.setZero(dof);
  scratch_.setZero(dof);
  previous_mass_.setZero(dof, dof);
  wrench_.setZero();
  wrench_due_ = false;
  last_data_ = nullptr;
  started_ = false;
}

void MomentumObserver::update(const JointVector& velocity, const JointVector& tau,
                              const model::Data& data, double period_s) noexcept {
  const int n = dof_;
  const auto mass = data.mass_matrix.topLeftCorner(n, n);
  const auto dq = velocity.head(n);
  auto momentum = momentum_.head(n);
  momentum.noalias() = mass * dq;
  if (!started_ || !(period_s > 0.0)) {
    initial_momentum_ = momentum_;
    integral_.setZero(n);
    residual_.setZero(n);
    previous_mass_.topLeftCorner(n, n) = mass;
    wrench_.setZero();
    wrench_due_ = false;
    started_ = true;
    return;
  }
  // C^T dq = dM/dt dq - C dq, with dM/dt over the period that ended: (M dq - M_prev dq) / T.
  auto rate = scratch_.head(n);
  rate.noalias() = previous_mass_.topLeftCorner(n, n) * dq;
  rate = (momentum - rate) / period_s - data.coriolis.head(n);
  // Explicit Euler with the residual of the previous cycle, as the continuous law reads.
  integral_.head(n) += period_s * (tau.head(n) + rate - data.gravity.head(n) + residual_.head(n));
  residual_.head(n) =
      config_.gain_per_s * (momentum - initial_momentum_.head(n) - integral_.head(n));
  previous_mass_.topLeftCorner(n, n) = mass;
  last_data_ = &data;
  wrench_due_ = true;
}

const Vector6d& MomentumObserver::wrench() const noexcept {
  if (!wrench_due_ || last_data_ == nullptr) {
    return wrench_;
  }
  // F = (J J^T + lambda^2 I)^-1 J r: the damped least-squares solution of J^T F = r. Column by
  // column, so that every product is of fixed-size 6-vectors (a third of the time of Eigen's
  // product of the dynamic-width Jacobian).
  Eigen::Matrix<double, 6, 6> normal =
      (config_.damping * config_.damping) * Eigen::Matrix<double, 6, 6>::Identity();
  Vector6d projected = Vector6d::Zero();
  for (int j = 0; j < dof_; ++j) {
    const Vector6d column = last_data_->jacobian.col(j);
    normal.noalias() += column * column.transpose();
    projected += residual_[j] * column;
  }
  wrench_ = solvePositiveDefinite(normal, projected);
  wrench_due_ = false;
  return wrench_;
}

}  // namespace comply::pipeline
