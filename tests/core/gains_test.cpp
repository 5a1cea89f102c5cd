#include "comply/core/gains.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>
#include <random>
#include <utility>

namespace comply {
namespace {

Matrix6d randomSpd(std::mt19937& rng, double floor) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Matrix6d a;
  for (int i = 0; i < 36; ++i) {
    a(i) = entry(rng);
  }
  return a * a.transpose() + floor * Matrix6d::Identity();
}

TEST(IsSymmetricPsd, AcceptsPsdAndRejectsTheRest) {
  EXPECT_TRUE(isSymmetricPsd(Eigen::Vector3d(100.0, 0.0, 50.0).asDiagonal().toDenseMatrix()));
  Eigen::Matrix3d asymmetric = Eigen::Matrix3d::Identity();
  asymmetric(0, 1) = 0.1;
  EXPECT_FALSE(isSymmetricPsd(asymmetric));
  EXPECT_FALSE(isSymmetricPsd(Eigen::Vector3d(100.0, -1.0, 50.0).asDiagonal().toDenseMatrix()));
  Eigen::Matrix3d indefinite;  // symmetric, positive diagonal, one negative eigenvalue
  indefinite << 1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0;
  EXPECT_FALSE(isSymmetricPsd(indefinite));
  Eigen::Matrix3d with_nan = Eigen::Matrix3d::Identity();
  with_nan(2, 2) = std::nan("");
  EXPECT_FALSE(isSymmetricPsd(with_nan));
}

TEST(DampingFromStiffness, IsTwoRootKOnThePrincipalAxes) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const Eigen::Vector3d principal(400.0, 100.0, 25.0);
  const Eigen::Matrix3d stiffness = rotation * principal.asDiagonal() * rotation.transpose();
  const Eigen::Matrix3d damping = dampingFromStiffness(stiffness, 0.7, 4.0);
  // 2 zeta sqrt(m k) per principal axis.
  const Eigen::Vector3d expected(2 * 0.7 * std::sqrt(4.0 * 400.0), 2 * 0.7 * std::sqrt(4.0 * 100.0),
                                 2 * 0.7 * std::sqrt(4.0 * 25.0));
  const Eigen::Matrix3d in_principal = rotation.transpose() * damping * rotation;
  EXPECT_LT((in_principal - Eigen::Matrix3d(expected.asDiagonal())).norm(), 1e-10);
}

// The defining property of critical damping on an inertia: D Lambda^-1 D = 4 K (each mode of
// M x'' + D x' + K x = 0 then has a double real pole).
void expectCritical(const Matrix6d& damping, const Matrix6d& stiffness, const Matrix6d& inertia) {
  const Matrix6d lhs = damping * inertia.inverse() * damping;
  EXPECT_LT((lhs - 4.0 * stiffness).norm(), 1e-9 * (1.0 + stiffness.norm()));
  EXPECT_LT((damping - damping.transpose()).norm(), 1e-9 * damping.norm());
}

TEST(CriticalDamping, SatisfiesTheCriticalDampingIdentity) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Matrix6d inertia = randomSpd(rng, 0.1);
    Matrix6d stiffness = Matrix6d::Zero();
    stiffness.diagonal() << 1000.0, 1000.0, 50.0, 30.0, 30.0, 10.0;
    expectCritical(criticalDamping(stiffness, inertia), stiffness, inertia);
  }
}

TEST(CriticalDamping, ReducesToTwoRootKMOnADiagonalInertia) {
  Matrix6d inertia = Matrix6d::Zero();
  inertia.diagonal() << 2.0, 3.0, 4.0, 0.1, 0.2, 0.3;
  Matrix6d stiffness = Matrix6d::Zero();
  stiffness.diagonal() << 500.0, 500.0, 50.0, 30.0, 20.0, 10.0;
  const Matrix6d damping = criticalDamping(stiffness, inertia);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(damping(i, i), 2.0 * std::sqrt(stiffness(i, i) * inertia(i, i)), 1e-10);
  }
}

/// Runs the tracker along a smoothly drifting inertia; returns the largest error relative to the
/// direct solution and the most sweeps any warm-started cycle needed.
std::pair<double, int> trackAlongDrift(const Vector6d& stiffness_diagonal) {
  std::mt19937 rng(11);
  const Matrix6d start = randomSpd(rng, 0.05);
  const Matrix6d drift = randomSpd(rng, 0.0);
  const Matrix6d stiffness = stiffness_diagonal.asDiagonal();
  CriticalDampingTracker tracker;
  double worst_relative_error = 0.0;
  int max_sweeps_after_first = 0;
  for (int cycle = 0; cycle < 200; ++cycle) {
    const Matrix6d inverse_inertia = start + 1e-3 * cycle * drift;
    Matrix6d damping;
    if (!tracker.compute(stiffness, inverse_inertia, damping)) {
      return {std::numeric_limits<double>::infinity(), 0};
    }
    const Matrix6d direct = criticalDamping(stiffness, inverse_inertia.inverse());
    worst_relative_error =
        std::max(worst_relative_error, (damping - direct).norm() / direct.norm());
    if (cycle > 0) {
      max_sweeps_after_first = std::max(max_sweeps_after_first, tracker.lastSweeps());
    }
  }
  return {worst_relative_error, max_sweeps_after_first};
}

/// Along the drift with `stiffness`: the direct solution within `tolerance` (relative), and the
/// point of the warm start, a smoothly changing inertia needing at most a couple of sweeps.
void expectTracksTheDirectSolution(const Vector6d& stiffness, double tolerance) {
  const auto [error, sweeps] = trackAlongDrift(stiffness);
  EXPECT_LT(error, tolerance);
  EXPECT_LE(sweeps, 3);
}

TEST(CriticalDampingTracker, MatchesTheDirectSolutionAlongASmoothSequence) {
  expectTracksTheDirectSolution((Vector6d() << 800.0, 800.0, 50.0, 40.0, 40.0, 10.0).finished(),
                                1e-10);
}

TEST(CriticalDampingTracker, HandlesAZeroStiffnessAxis) {
  // sqrt() of an eigenvalue that is zero up to rounding (~1e-14 of the largest) is ~1e-7 of
  // sqrt(largest): both solutions carry that error, so the tolerance is looser here.
  expectTracksTheDirectSolution((Vector6d() << 800.0, 800.0, 0.0, 40.0, 40.0, 10.0).finished(),
                                1e-6);
}

TEST(CriticalDampingTracker, RefusesAnInverseInertiaThatIsNotPositiveDefinite) {
  CriticalDampingTracker tracker;
  Matrix6d damping = Matrix6d::Constant(7.0);
  Matrix6d singular = Matrix6d::Identity();
  singular(5, 5) = -1.0;
  EXPECT_FALSE(tracker.compute(Matrix6d::Identity(), singular, damping));
  EXPECT_EQ(damping, Matrix6d::Constant(7.0));
}

TEST(SymmetricEigenJacobi, AgreesWithEigenFromColdAndWarmStarts) {
  std::mt19937 rng(5);
  Matrix6d basis = Matrix6d::Identity();
  for (int trial = 0; trial < 10; ++trial) {
    const Matrix6d matrix = randomSpd(rng, 0.0) - 2.0 * Matrix6d::Identity();  // indefinite too
    Vector6d eigenvalues;
    symmetricEigenJacobi(matrix, basis, eigenvalues);  // warm from the previous, unrelated basis
    EXPECT_LT((basis * eigenvalues.asDiagonal() * basis.transpose() - matrix).norm(),
              1e-12 * matrix.norm());
    EXPECT_LT((basis.transpose() * basis - Matrix6d::Identity()).norm(), 1e-13);
    Vector6d sorted = eigenvalues;
    std::sort(sorted.data(), sorted.data() + 6);
    const Eigen::SelfAdjointEigenSolver<Matrix6d> reference(matrix);
    EXPECT_LT((sorted - reference.eigenvalues()).norm(), 1e-12 * matrix.norm());
  }
}

TEST(SymmetricEigenJacobi, RepairsANonOrthonormalStartingBasis) {
  Matrix6d basis = Matrix6d::Identity();
  basis(0, 1) = 0.5;  // not orthonormal
  Matrix6d matrix = Matrix6d::Zero();
  matrix.diagonal() << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  matrix(0, 5) = matrix(5, 0) = 0.5;
  Vector6d eigenvalues;
  symmetricEigenJacobi(matrix, basis, eigenvalues);
  EXPECT_LT((basis * eigenvalues.asDiagonal() * basis.transpose() - matrix).norm(), 1e-12);
}

}  // namespace
}  // namespace comply
