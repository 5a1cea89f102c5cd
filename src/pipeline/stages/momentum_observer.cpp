// The momentum observer's discrete update (see momentum_observer.hpp).

#include "comply/pipeline/momentum_observer.hpp"

namespace comply::pipeline {
namespace {

/// x with A x = b for a symmetric positive definite 6x6 A: LDL^T without pivoting (stable for a
/// positive definite matrix), written out with its loops unrolled, so that L stays in registers
/// and only the chain of six divisions is left: half the time of the same loops rolled, a quarter
/// of Eigen's LLT on a 6x6. Reads A's lower triangle.
Vector6d solvePositiveDefinite(const Eigen::Matrix<double, 6, 6>& a, const Vector6d& b) noexcept {
  double l[6][6];
  double d[6];
  double d_inverse[6];
#pragma GCC unroll 6
  for (int j = 0; j < 6; ++j) {
    double dj = a(j, j);
#pragma GCC unroll 6
    for (int k = 0; k < j; ++k) {
      dj -= l[j][k] * l[j][k] * d[k];
    }
    d[j] = dj;
    d_inverse[j] = 1.0 / dj;
#pragma GCC unroll 6
    for (int i = j + 1; i < 6; ++i) {
      double lij = a(i, j);
#pragma GCC unroll 6
      for (int k = 0; k < j; ++k) {
        lij -= l[i][k] * l[j][k] * d[k];
      }
      l[i][j] = lij * d_inverse[j];
    }
  }
  Vector6d x = b;
#pragma GCC unroll 6
  for (int i = 1; i < 6; ++i) {  // L y = b
#pragma GCC unroll 6
    for (int k = 0; k < i; ++k) {
      x[i] -= l[i][k] * x[k];
    }
  }
#pragma GCC unroll 6
  for (int i = 0; i < 6; ++i) {  // D z = y
    x[i] *= d_inverse[i];
  }
#pragma GCC unroll 6
  for (int i = 4; i >= 0; --i) {  // L^T x = z
#pragma GCC unroll 6
    for (int k = i + 1; k < 6; ++k) {
      x[i] -= l[k][i] * x[k];
    }
  }
  return x;
}

/// The residual's step for N joints (fixed for the common arms, Eigen::Dynamic otherwise): the
/// matrix-vector products of fixed size vectorise, those of the capacity-sized JointMatrix do not.
/// Arrays are column-major n x n and n long; `momentum` holds M dq on entry.
template <int N>
void residualStep(int n, const double* mass, double* previous_mass, const double* dq,
                  const double* tau, const double* coriolis, const double* gravity,
                  const double* initial_momentum, const double* momentum, double period_s,
                  double gain, double* integral, double* residual) noexcept {
  using Square = Eigen::Matrix<double, N, N>;
  using Column = Eigen::Matrix<double, N, 1>;
  const Eigen::Map<const Square> m(mass, n, n);
  Eigen::Map<Square> m_previous(previous_mass, n, n);
  const Eigen::Map<const Column> v(dq, n);
  const Eigen::Map<const Column> p(momentum, n);
  Eigen::Map<Column> r(residual, n);
  Eigen::Map<Column> integrated(integral, n);
  // T C^T dq = T (dM/dt dq - C dq) = M dq - M_prev dq - T C dq: dM/dt over the period that
  // ended. Explicit Euler with the residual of the previous cycle, as the continuous law reads.
  Column step = p;
  step.noalias() -= m_previous * v;
  step += period_s * (Eigen::Map<const Column>(tau, n) - Eigen::Map<const Column>(coriolis, n) -
                      Eigen::Map<const Column>(gravity, n) + r);
  integrated += step;
  r = gain * (p - Eigen::Map<const Column>(initial_momentum, n) - integrated);
  m_previous = m;
}

/// F = (J J^T + lambda^2 I)^-1 J r: the damped least-squares solution of J^T F = r, for N joints
/// (fixed for the common arms, Eigen::Dynamic otherwise). `jacobian` is column-major 6 x n. The
/// fixed-size product J J^T vectorises whole; column by column it spilled to the stack and cost
/// the cycle twice as much.
template <int N>
Vector6d dampedWrench(int n, const double* jacobian, const double* residual,
                      double damping) noexcept {
  const Eigen::Map<const Eigen::Matrix<double, 6, N>> j(jacobian, 6, n);
  Eigen::Matrix<double, 6, 6> normal;
  normal.noalias() = j * j.transpose();
  normal.diagonal().array() += damping * damping;
  const Vector6d projected = j * Eigen::Map<const Eigen::Matrix<double, N, 1>>(residual, n);
  return solvePositiveDefinite(normal, projected);
}

}  // namespace

void MomentumObserver::configure(const ObserverConfig& config, int dof,
                                 const JointVector& rotor_inertia) noexcept {
  config_ = config;
  dof_ = dof;
  rotor_inertia_ =
      rotor_inertia.size() == dof ? rotor_inertia : JointVector(JointVector::Zero(dof));
  initial_momentum_.setZero(dof);
  momentum_.setZero(dof);
  integral_.setZero(dof);
  residual_.setZero(dof);
  previous_mass_.setZero(dof, dof);
  wrench_.setZero();
  started_ = false;
}

void MomentumObserver::update(const JointVector& velocity, const JointVector& tau,
                              const model::Data& data, double period_s) noexcept {
  const int n = dof_;
  const auto mass = data.mass_matrix.topLeftCorner(n, n);
  const auto dq = velocity.head(n);
  auto momentum = momentum_.head(n);
  const auto rotors = rotor_inertia_.head(n);
  momentum.noalias() = mass * dq;
  momentum -= rotors.cwiseProduct(dq);
  if (!started_ || !(period_s > 0.0)) {
    initial_momentum_ = momentum_;
    integral_.setZero(n);
    residual_.setZero(n);
    previous_mass_.topLeftCorner(n, n) = mass;
    previous_mass_.diagonal().head(n) -= rotors;
    wrench_.setZero();
    started_ = true;
    return;
  }
  const auto step = n == 7   ? &residualStep<7>
                    : n == 6 ? &residualStep<6>
                             : &residualStep<Eigen::Dynamic>;
  step(n, data.mass_matrix.data(), previous_mass_.data(), velocity.data(), tau.data(),
       data.coriolis.data(), data.gravity.data(), initial_momentum_.data(), momentum_.data(),
       period_s, config_.gain_per_s, integral_.data(), residual_.data());
  previous_mass_.diagonal().head(n) -= rotors;  // the step kept M(q) as it is
  const auto solve = n == 7   ? &dampedWrench<7>
                     : n == 6 ? &dampedWrench<6>
                              : &dampedWrench<Eigen::Dynamic>;
  wrench_ = solve(n, data.jacobian.data(), residual_.data(), config_.damping);
}

}  // namespace comply::pipeline
