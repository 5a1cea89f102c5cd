// The online path frame from measured positions: it keeps the initial frame until it has seen a
// window's worth of motion, then gives z along the direction of travel on a straight line and the
// closed-form Frenet frame on a circle; noise below the sample spacing never moves it, noise on a
// moving path tilts it by little; a reversal never turns it sideways; updates allocate nothing.

#include "comply/task/online_path_frame.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "allocation_counter.hpp"

namespace comply::task {
namespace {

constexpr double kPeriodS = 0.001;

void expectOrthonormal(const Eigen::Matrix3d& frame) {
  EXPECT_LT((frame.transpose() * frame - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  EXPECT_NEAR(frame.determinant(), 1.0, 1e-9);
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

/// A TCP frame pointing down (z = -base z), as a tool above a table holds it.
Eigen::Matrix3d toolDown() {
  return Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

TEST(OnlinePathFrame, KeepsTheInitialFrameUntilAWindowOfMotion) {
  OnlinePathFrame estimator({}, toolDown());
  EXPECT_FALSE(estimator.tracking());
  EXPECT_TRUE(estimator.frame().isApprox(toolDown()));
  const Eigen::Vector3d start(0.4, 0.0, 0.3);
  for (int k = 0; k < 100; ++k) {  // at rest
    estimator.update(k * kPeriodS, start);
  }
  EXPECT_FALSE(estimator.tracking());
  EXPECT_EQ(estimator.pathLength(), 0.0);
  EXPECT_EQ(estimator.speed(), 0.0);
  // Sideways at 10 mm/s: 7 spacings (3.5 mm) fill the window of 8.
  const double speed = 0.01;
  double t = 0.1;
  while (!estimator.tracking()) {
    EXPECT_TRUE(estimator.frame().isApprox(toolDown()));
    t += kPeriodS;
    estimator.update(t, start + Eigen::Vector3d(speed * (t - 0.1), 0.0, 0.0));
  }
  EXPECT_NEAR(estimator.pathLength(), 3.5e-3, 1e-5);
  // The window still holds the wait at the start; once it has moved on, the speed is the TCP's.
  EXPECT_LT(estimator.speed(), speed);
  for (int k = 0; k < 500; ++k) {
    t += kPeriodS;
    estimator.update(t, start + Eigen::Vector3d(speed * (t - 0.1), 0.0, 0.0));
  }
  EXPECT_NEAR(estimator.speed(), speed, 0.03 * speed);  // kept samples lie up to a cycle late
}

TEST(OnlinePathFrame, StraightLineGivesZAlongTheTravelAndKeepsTheInitialNormal) {
  OnlinePathFrame estimator({}, toolDown());
  const Eigen::Vector3d direction = Eigen::Vector3d(0.2, -0.1, -1.0).normalized();
  for (int k = 0; k < 1000; ++k) {
    estimator.update(k * kPeriodS,
                     Eigen::Vector3d(0.4, 0.0, 0.3) + 0.02 * k * kPeriodS * direction);
    if (estimator.tracking()) {
      expectOrthonormal(estimator.frame());
      ASSERT_LT((estimator.frame().col(2) - direction).norm(), 1e-9);
    }
  }
  ASSERT_TRUE(estimator.tracking());
  EXPECT_LT(estimator.curvature(), 1e-6);
  // No curvature: x is the initial x made orthogonal to the travel, not an arbitrary direction.
  const Eigen::Vector3d x0 = toolDown().col(0);
  const Eigen::Vector3d expected_x = (x0 - x0.dot(direction) * direction).normalized();
  EXPECT_LT((estimator.frame().col(0) - expected_x).norm(), 1e-9);
}

TEST(OnlinePathFrame, CircleGivesItsCurvatureAndTheNormalTowardsTheCentre) {
  // Radius 0.1 m in a plane tilted 30 deg about base x, at 20 mm/s.
  const double radius = 0.1;
  const Eigen::Matrix3d plane =
      Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d centre(0.4, 0.1, 0.3);
  OnlinePathFrame estimator;
  int tracked = 0;
  for (int k = 0; k < 2000; ++k) {
    const double angle = 0.02 * k * kPeriodS / radius;
    const Eigen::Vector3d radial = plane * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
    estimator.update(k * kPeriodS, centre + radius * radial);
    if (!estimator.tracking()) {
      continue;
    }
    ++tracked;
    const Eigen::Vector3d tangent = plane * Eigen::Vector3d(-std::sin(angle), std::cos(angle), 0);
    expectOrthonormal(estimator.frame());
    // The fit at the newest kept sample: at most one spacing (0.5 mm, 0.29 deg) behind.
    EXPECT_LT(angleDeg(estimator.frame().col(2), tangent), 0.35);
    EXPECT_LT(angleDeg(estimator.frame().col(0), -radial), 0.35);
    EXPECT_LT(angleDeg(estimator.frame().col(1), plane.col(2)), 1e-3);
    EXPECT_NEAR(estimator.curvature(), 1.0 / radius, 0.01 / radius);
  }
  EXPECT_GT(tracked, 1800);  // after 3.5 mm, 175 cycles
}

TEST(OnlinePathFrame, NoiseAtRestNeverMovesItAndOnTheMoveTiltsItByLittle) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-2e-5, 2e-5);  // +-20 um, an encoder's worth
  const auto noisy = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x() + noise(random), p.y() + noise(random), p.z() + noise(random));
  };
  OnlinePathFrame estimator({}, toolDown());
  const Eigen::Vector3d start(0.4, 0.0, 0.3);
  for (int k = 0; k < 5000; ++k) {
    estimator.update(k * kPeriodS, noisy(start));
  }
  EXPECT_FALSE(estimator.tracking());
  EXPECT_TRUE(estimator.frame().isApprox(toolDown()));

  const Eigen::Vector3d direction = Eigen::Vector3d(0.0, 0.3, -1.0).normalized();
  double worst_deg = 0.0;
  for (int k = 0; k < 3000; ++k) {
    estimator.update(5.0 + k * kPeriodS, noisy(start + 0.0125 * k * kPeriodS * direction));
    if (estimator.tracking()) {
      expectOrthonormal(estimator.frame());
      worst_deg = std::max(worst_deg, angleDeg(estimator.frame().col(2), direction));
    }
  }
  ASSERT_TRUE(estimator.tracking());
  EXPECT_LT(worst_deg, 3.0);
}

TEST(OnlinePathFrame, AReversalNeverTurnsTheTangentSideways) {
  OnlinePathFrame estimator;
  const Eigen::Vector3d start(0.4, 0.0, 0.3);
  double x = 0.0;
  for (int k = 0; k < 2000; ++k) {
    x += (k < 1000 ? 1.0 : -1.0) * 0.02 * kPeriodS;  // 20 mm out, then back
    estimator.update(k * kPeriodS, start + Eigen::Vector3d(x, 0.0, 0.0));
    if (estimator.tracking()) {
      expectOrthonormal(estimator.frame());
      ASSERT_GT(std::abs(estimator.frame().col(2).x()), 1.0 - 1e-9) << "at cycle " << k;
    }
    if (k == 999) {
      EXPECT_GT(estimator.frame().col(2).x(), 0.0);
    }
  }
  EXPECT_LT(estimator.frame().col(2).x(), 0.0);  // the way back, once the window has passed
}

TEST(OnlinePathFrame, ResetForgetsThePath) {
  OnlinePathFrame estimator;
  for (int k = 0; k < 300; ++k) {
    estimator.update(k * kPeriodS, Eigen::Vector3d(0.02 * k * kPeriodS, 0.0, 0.0));
  }
  ASSERT_TRUE(estimator.tracking());
  estimator.reset(toolDown());
  EXPECT_FALSE(estimator.tracking());
  EXPECT_TRUE(estimator.frame().isApprox(toolDown()));
  EXPECT_EQ(estimator.pathLength(), 0.0);
}

TEST(OnlinePathFrame, UpdatesAllocateNothingAndBadOptionsThrow) {
  OnlinePathFrame estimator;
  testing::AllocationCounter counter;
  counter.start();
  for (int k = 0; k < 2000; ++k) {
    const double angle = 0.2 * k * kPeriodS;
    estimator.update(k * kPeriodS, 0.1 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0));
  }
  EXPECT_EQ(counter.stop(), 0U);
  EXPECT_TRUE(estimator.tracking());
  EXPECT_THROW(OnlinePathFrame({.sample_spacing_m = 0.0}), std::invalid_argument);
  EXPECT_THROW(OnlinePathFrame({.window_samples = 2}), std::invalid_argument);
}

}  // namespace
}  // namespace comply::task
