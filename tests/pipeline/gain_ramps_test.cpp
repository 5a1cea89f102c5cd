// The gain ramps on their own (gain_ramps.hpp): a matrix moves along the straight line to its
// target, a diagonal entry by entry, the frame along the shortest arc, each by at most one step,
// and each lands on its target bit for bit.

#include "comply/pipeline/gain_ramps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace comply::pipeline {
namespace {

// 1e16 + (1 - 1e16) rounds to 0, not 1: landing on a target must not go through the difference.
constexpr double kFar = 1e16;

TEST(Approach, MovesAlongTheStraightLineByAtMostOneStep) {
  double current[3] = {0.0, 0.0, 4.0};
  const double target[3] = {10.0, 5.0, 4.0};
  EXPECT_FALSE(approach(current, target, 3, 2.0));
  // The largest change, 10, limits all of them to a fifth of their way.
  EXPECT_DOUBLE_EQ(current[0], 2.0);
  EXPECT_DOUBLE_EQ(current[1], 1.0);
  EXPECT_DOUBLE_EQ(current[2], 4.0);
}

TEST(Approach, ArrivesOnTheTargetBitForBit) {
  double current[2] = {kFar, 0.0};
  const double target[2] = {1.0, 0.3};
  EXPECT_TRUE(approach(current, target, 2, 2.0 * kFar));
  EXPECT_EQ(current[0], 1.0);
  EXPECT_EQ(current[1], 0.3);
}

TEST(ApproachEach, StepsEveryEntryOnItsOwn) {
  double current[3] = {0.0, 0.0, 5.0};
  const double target[3] = {10.0, 1.0, 0.0};
  EXPECT_FALSE(approachEach(current, target, 3, 2.0));
  EXPECT_EQ(current[0], 2.0);  // limited
  EXPECT_EQ(current[1], 1.0);  // arrived, not dragged along the first
  EXPECT_EQ(current[2], 3.0);  // a decrease, by the same step
  EXPECT_FALSE(approachEach(current, target, 3, 2.0));
  EXPECT_FALSE(approachEach(current, target, 3, 2.0));
  EXPECT_EQ(current[2], 0.0);  // lands on zero, never below
  current[0] = 9.5;
  EXPECT_TRUE(approachEach(current, target, 3, 2.0));
  EXPECT_EQ(current[0], 10.0);
}

TEST(ApproachFrame, TurnsAtMostOneStepTowardTheGoal) {
  const Eigen::Quaterniond goal(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  Eigen::Quaterniond frame = Eigen::Quaterniond::Identity();
  EXPECT_FALSE(approachFrame(frame, goal, 0.1));
  EXPECT_NEAR(frame.angularDistance(Eigen::Quaterniond::Identity()), 0.1, 1e-12);
  EXPECT_NEAR(frame.angularDistance(goal), std::numbers::pi / 2 - 0.1, 1e-12);
  const Eigen::AngleAxisd turned(frame);
  EXPECT_NEAR(std::abs(turned.axis().z()), 1.0, 1e-12);  // about the goal's own axis
}

TEST(ApproachFrame, ArrivesOnTheGoalItself) {
  const Eigen::Quaterniond goal(
      Eigen::AngleAxisd(0.05, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()));
  Eigen::Quaterniond frame = Eigen::Quaterniond::Identity();
  EXPECT_TRUE(approachFrame(frame, goal, 0.1));
  EXPECT_TRUE(frame.coeffs() == goal.coeffs());
}

TEST(Blend, MovesTheFractionOfTheWayAndAllOfItExactly) {
  double current[2] = {0.0, 8.0};
  const double target[2] = {4.0, 0.0};
  blend(current, target, 2, 0.25);
  EXPECT_DOUBLE_EQ(current[0], 1.0);
  EXPECT_DOUBLE_EQ(current[1], 6.0);
  double far[1] = {kFar};
  const double one[1] = {1.0};
  blend(far, one, 1, 1.0);
  EXPECT_EQ(far[0], 1.0);
  blend(far, one, 1, 0.0);
  EXPECT_EQ(far[0], 1.0);
}

}  // namespace
}  // namespace comply::pipeline
