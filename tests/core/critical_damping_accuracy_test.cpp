// The fast ratio-damping D (CriticalDampingTracker: Cholesky of Lambda^-1, warm-started Jacobi
// with a relative stopping criterion, second-order square root) held against an independent
// reference: Eigen's generalised eigen solver on K v = w Lambda v with V^T Lambda V = I, giving
// D = Lambda V diag(2 sqrt(w)) V^T Lambda. The promise checked is the one the law makes: within
// 1e-6 relative on every call, whatever the previous call left in the warm start.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <random>

#include "comply/core/gains.hpp"

namespace comply {
namespace {

constexpr double kPromisedRelativeError = 1e-6;

Matrix6d referenceDamping(const Matrix6d& stiffness, const Matrix6d& inertia) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> eigen(stiffness, inertia);
  const Matrix6d modes = inertia * eigen.eigenvectors();
  const Vector6d frequency = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return modes * (2.0 * frequency).asDiagonal() * modes.transpose();
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

/// Block-diagonal K: translational and rotational principal stiffnesses spread over two decades
/// (anisotropic), turned by one random task frame, as the law builds it.
Matrix6d anisotropicStiffness(std::mt19937& rng) {
  std::uniform_real_distribution<double> log_stiffness(0.0, 2.0);
  const Eigen::Matrix3d task = randomRotation(rng);
  Eigen::Vector3d translational;
  Eigen::Vector3d rotational;
  for (int i = 0; i < 3; ++i) {
    translational[i] = 20.0 * std::pow(10.0, log_stiffness(rng));
    rotational[i] = 0.5 * std::pow(10.0, log_stiffness(rng));
  }
  Matrix6d stiffness = Matrix6d::Zero();
  stiffness.topLeftCorner<3, 3>() = task * translational.asDiagonal() * task.transpose();
  stiffness.bottomRightCorner<3, 3>() = task * rotational.asDiagonal() * task.transpose();
  return stiffness;
}

/// A Cartesian inertia like an arm's: masses of a few kg, rotational inertias of 1e-2..1, coupled.
Matrix6d randomInertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Matrix6d a;
  for (int i = 0; i < 36; ++i) {
    a(i) = entry(rng);
  }
  Vector6d scale;
  scale << 2.0, 2.0, 2.0, 0.3, 0.3, 0.3;
  return scale.asDiagonal() * (a * a.transpose() + 0.05 * Matrix6d::Identity()) *
         scale.asDiagonal();
}

double relativeError(const Matrix6d& actual, const Matrix6d& expected) {
  return (actual - expected).norm() / expected.norm();
}

TEST(CriticalDampingAccuracy, RandomAnisotropicPairsInRotatedTaskFrames) {
  std::mt19937 rng(2024);
  CriticalDampingTracker tracker;  // warm start from the previous, unrelated pair
  double worst = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const Matrix6d stiffness = anisotropicStiffness(rng);
    const Matrix6d inertia = randomInertia(rng);
    Matrix6d damping;
    ASSERT_TRUE(tracker.compute(stiffness, inertia.inverse(), damping));
    worst = std::max(worst, relativeError(damping, referenceDamping(stiffness, inertia)));
  }
  EXPECT_LT(worst, kPromisedRelativeError);
}

TEST(CriticalDampingAccuracy, NearlyRepeatedAndRepeatedEigenvalues) {
  // K = k Lambda (+ a tiny, random symmetric perturbation): all six generalised eigenvalues equal,
  // or within 1e-9 relative of each other, where eigenvectors are arbitrary; D is not.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  CriticalDampingTracker tracker;
  for (const double spread : {0.0, 1e-12, 1e-9, 1e-6}) {
    for (int trial = 0; trial < 50; ++trial) {
      const Matrix6d inertia = randomInertia(rng);
      Matrix6d perturbation;
      for (int i = 0; i < 36; ++i) {
        perturbation(i) = entry(rng);
      }
      perturbation = (0.5 * (perturbation + perturbation.transpose())).eval();
      const Matrix6d stiffness = 400.0 * (inertia + spread * inertia.norm() * perturbation);
      Matrix6d damping;
      ASSERT_TRUE(tracker.compute(stiffness, inertia.inverse(), damping));
      EXPECT_LT(relativeError(damping, referenceDamping(stiffness, inertia)),
                kPromisedRelativeError)
          << "spread " << spread << ", trial " << trial;
    }
  }
}

TEST(CriticalDampingAccuracy, IsotropicStiffnessOnANearlyIsotropicInertia) {
  // The default gains on a near-symmetric posture: two triples of nearly repeated eigenvalues.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> entry(-1e-8, 1e-8);
  Matrix6d stiffness = Matrix6d::Zero();
  stiffness.diagonal() << 500.0, 500.0, 500.0, 30.0, 30.0, 30.0;
  CriticalDampingTracker tracker;
  for (int trial = 0; trial < 100; ++trial) {
    Matrix6d inertia = Matrix6d::Zero();
    inertia.diagonal() << 3.0, 3.0, 3.0, 0.05, 0.05, 0.05;
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c <= r; ++c) {
        inertia(r, c) += entry(rng);
        inertia(c, r) = inertia(r, c);
      }
    }
    Matrix6d damping;
    ASSERT_TRUE(tracker.compute(stiffness, inertia.inverse(), damping));
    EXPECT_LT(relativeError(damping, referenceDamping(stiffness, inertia)), kPromisedRelativeError);
  }
}

TEST(CriticalDampingAccuracy, EveryCycleOfADriftingInertiaWithStiffnessSteps) {
  // The control-loop case: Lambda drifts every cycle, the task frame turns, and K jumps every
  // 100 cycles (a new command). Each cycle must be right at once, not after a few.
  std::mt19937 rng(99);
  const Matrix6d start = randomInertia(rng);
  const Matrix6d drift = randomInertia(rng);
  CriticalDampingTracker tracker;
  Matrix6d stiffness = anisotropicStiffness(rng);
  double worst = 0.0;
  for (int cycle = 0; cycle < 1000; ++cycle) {
    if (cycle % 100 == 0) {
      stiffness = anisotropicStiffness(rng);
    }
    const double phase = 2.0 * M_PI * cycle / 1000.0;
    const Matrix6d inertia = start + 0.5 * (1.0 + std::sin(phase)) * drift;
    Matrix6d damping;
    ASSERT_TRUE(tracker.compute(stiffness, inertia.inverse(), damping));
    worst = std::max(worst, relativeError(damping, referenceDamping(stiffness, inertia)));
  }
  EXPECT_LT(worst, kPromisedRelativeError);
  EXPECT_LE(tracker.lastSweeps(), 2);  // warm: the cheap path, not a cold solve every cycle
}

TEST(CriticalDampingAccuracy, IllConditionedInertia) {
  // A near-singular posture: Lambda's eigenvalues spread over six decades, the most the law's
  // regularisation (1e-6 added to Lambda^-1, whose norm is of order one) lets through. Forming D
  // from a factor of Lambda^-1 loses accuracy with the condition number (about 4e-8 here, 5e-5 at
  // eight decades, the same before and after the fast path: it is the formulation's).
  std::mt19937 rng(5);
  CriticalDampingTracker tracker;
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Matrix<double, 6, 6> basis =
        Eigen::HouseholderQR<Matrix6d>(randomInertia(rng)).householderQ();
    Vector6d spectrum;
    spectrum << 1e-2, 1e-1, 1.0, 10.0, 1e2, 1e4;
    const Matrix6d inertia = basis * spectrum.asDiagonal() * basis.transpose();
    const Matrix6d stiffness = anisotropicStiffness(rng);
    Matrix6d damping;
    ASSERT_TRUE(tracker.compute(stiffness, inertia.inverse(), damping));
    EXPECT_LT(relativeError(damping, referenceDamping(stiffness, inertia)), kPromisedRelativeError);
  }
}

}  // namespace
}  // namespace comply
