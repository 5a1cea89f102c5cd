// The last stage before the hardware: low-pass, finite check, rate limit, effort limit, in that
// order. Each stage is isolated by making the others inactive (alpha = 1, huge limits), then the
// ordering is pinned with inputs where a different order would give a different torque.

#include "comply/pipeline/torque_shaper.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "command_bits.hpp"

namespace comply::pipeline {
namespace {

using test::joints;

constexpr double kTight = 1e-12;
constexpr double kPeriod = 0.001;  // 1 kHz
constexpr double kInactive = 1e9;  // a rate or effort limit that never binds
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

ShapingLimits limits(double alpha, JointVector rate, JointVector effort) {
  return ShapingLimits{alpha, std::move(rate), std::move(effort)};
}

ShapingLimits filterOnly(double alpha, int dof) {
  return limits(alpha, JointVector::Constant(dof, kInactive),
                JointVector::Constant(dof, kInactive));
}

void expectJoints(const JointVector& actual, std::initializer_list<double> expected) {
  ASSERT_EQ(actual.size(), static_cast<Eigen::Index>(expected.size()));
  Eigen::Index i = 0;
  for (const double value : expected) {
    EXPECT_NEAR(actual[i], value, kTight) << "joint " << i;
    ++i;
  }
}

/// One cycle of `shaper` on the torque `in`: the torque it sends is `out`.
void expectShaped(TorqueShaper& shaper, std::initializer_list<double> in,
                  std::initializer_list<double> out, bool filter = true) {
  JointVector torque = joints(in);
  shaper.apply(torque, kPeriod, filter);
  expectJoints(torque, out);
}

TEST(TorqueShaper, StartsFromZeroSizedByTheEffortLimit) {
  const TorqueShaper shaper(filterOnly(0.5, 3));
  EXPECT_EQ(shaper.lastOutput(), JointVector::Zero(3));
}

TEST(TorqueShaper, LowPassFollowsItsRecurrence) {
  TorqueShaper shaper(filterOnly(0.25, 2));
  JointVector torque = joints({4.0, -8.0});
  // 0.25 * 4 + 0.75 * 0 = 1
  EXPECT_TRUE(shaper.apply(torque, kPeriod).finite);
  expectJoints(torque, {1.0, -2.0});
  // 0.25 * 4 + 0.75 * 1 = 1.75
  expectShaped(shaper, {4.0, -8.0}, {1.75, -3.5});
  // 0.25 * 0 + 0.75 * 1.75 = 1.3125
  expectShaped(shaper, {0.0, 0.0}, {1.3125, -2.625});
  expectJoints(shaper.lastOutput(), {1.3125, -2.625});
}

TEST(TorqueShaper, UnfilteredPassSkipsTheLowPassButSeedsIt) {
  TorqueShaper shaper(filterOnly(0.25, 1));
  expectShaped(shaper, {4.0}, {4.0}, /*filter=*/false);
  // The next filtered cycle continues from the torque actually sent: 0.75 * 4 = 3.
  expectShaped(shaper, {0.0}, {3.0});
}

TEST(TorqueShaper, NonFiniteTorqueRepeatsTheLastOutput) {
  TorqueShaper shaper(filterOnly(0.5, 3));
  shaper.reset(joints({2.0, -2.0, 1.0}));
  JointVector torque = joints({kNaN, 6.0, kInf});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_FALSE(result.finite);
  EXPECT_EQ(result.rate_limited, 0);
  EXPECT_EQ(result.effort_limited, 0);
  expectJoints(torque, {2.0, -2.0, 1.0});  // every joint held, not only the bad ones
  expectJoints(shaper.lastOutput(), {2.0, -2.0, 1.0});
}

TEST(TorqueShaper, NonFiniteTorqueDoesNotPoisonTheFilter) {
  TorqueShaper shaper(filterOnly(0.5, 1));
  shaper.reset(joints({2.0}));
  JointVector torque = joints({kNaN});
  shaper.apply(torque, kPeriod);
  // The filter state is still 2, so the next cycle gives 0.5 * 6 + 0.5 * 2 = 4, not NaN.
  torque = joints({6.0});
  EXPECT_TRUE(shaper.apply(torque, kPeriod).finite);
  expectJoints(torque, {4.0});
}

TEST(TorqueShaper, NonFiniteCycleLeavesTheFilterStateAsItWas) {
  // alpha 0.5, step 2: the filter state (4) differs from the output (2), so a NaN cycle that
  // re-seeded the filter from the output would show: 0.5 * 0 + 0.5 * 2 = 1 instead of 2.
  TorqueShaper shaper(limits(0.5, joints({2000.0}), joints({kInactive})));
  expectShaped(shaper, {8.0}, {2.0});
  expectShaped(shaper, {kNaN}, {2.0});
  expectShaped(shaper, {0.0}, {2.0});
}

TEST(TorqueShaper, NonFiniteIsCaughtWithoutTheFilterToo) {
  TorqueShaper shaper(filterOnly(1.0, 1));
  shaper.reset(joints({1.5}));
  JointVector torque = joints({-kInf});
  EXPECT_FALSE(shaper.apply(torque, kPeriod, /*filter=*/false).finite);
  expectJoints(torque, {1.5});
}

TEST(TorqueShaper, HeldTorqueIsTheLimitedOutputNotTheFilterState) {
  TorqueShaper shaper(limits(1.0, joints({kInactive}), joints({10.0})));
  expectShaped(shaper, {100.0}, {10.0});
  expectShaped(shaper, {kNaN}, {10.0});
}

TEST(TorqueShaper, RateLimitBoundsTheStepPerJoint) {
  // rate * period: 1 N m and 0.5 N m per cycle.
  TorqueShaper shaper(
      limits(1.0, joints({1000.0, 500.0, 1000.0}), JointVector::Constant(3, kInactive)));
  JointVector torque = joints({5.0, -5.0, 0.25});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_TRUE(result.finite);
  EXPECT_EQ(result.rate_limited, 2);
  EXPECT_EQ(result.effort_limited, 0);
  expectJoints(torque, {1.0, -0.5, 0.25});
  // Next cycle continues from the limited output, not from the request.
  expectShaped(shaper, {5.0, -5.0, 0.25}, {2.0, -1.0, 0.25});
}

TEST(TorqueShaper, RateLimitScalesWithTheMeasuredPeriod) {
  const ShapingLimits rate_only = limits(1.0, joints({1000.0}), joints({kInactive}));
  TorqueShaper fast(rate_only);
  TorqueShaper slow(rate_only);
  JointVector fast_torque = joints({10.0});
  JointVector slow_torque = joints({10.0});
  fast.apply(fast_torque, 0.001);
  slow.apply(slow_torque, 0.004);
  expectJoints(fast_torque, {1.0});
  expectJoints(slow_torque, {4.0});
}

TEST(TorqueShaper, ZeroPeriodHoldsTheTorque) {
  TorqueShaper shaper(limits(1.0, joints({1000.0}), joints({kInactive})));
  shaper.reset(joints({3.0}));
  JointVector torque = joints({-7.0});
  EXPECT_EQ(shaper.apply(torque, 0.0).rate_limited, 1);
  expectJoints(torque, {3.0});
}

TEST(TorqueShaper, EffortLimitClampsBothSigns) {
  TorqueShaper shaper(limits(1.0, JointVector::Constant(3, kInactive), joints({10.0, 3.0, 3.0})));
  JointVector torque = joints({12.0, -7.0, 2.5});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_EQ(result.effort_limited, 2);
  EXPECT_EQ(result.rate_limited, 0);
  expectJoints(torque, {10.0, -3.0, 2.5});
}

TEST(TorqueShaper, EffortLimitAppliesAfterTheRateLimit) {
  // Rate first: 5 -> 1 (step 1), then effort: 1 -> 0.5; both count. Were the effort clamp first,
  // 0.5 would pass the rate limit untouched and rate_limited would be 0.
  TorqueShaper shaper(limits(1.0, joints({1000.0}), joints({0.5})));
  JointVector torque = joints({5.0});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_EQ(result.rate_limited, 1);
  EXPECT_EQ(result.effort_limited, 1);
  expectJoints(torque, {0.5});
}

TEST(TorqueShaper, EffortLimitWinsOverTheRateLimit) {
  // Seeded above the effort limit (e.g. a measured effort): the output drops to the limit at
  // once, a larger step than the rate limit allows, because the effort limit is the hard one.
  TorqueShaper shaper(limits(1.0, joints({1000.0}), joints({10.0})));
  shaper.reset(joints({20.0}));
  JointVector torque = joints({20.0});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_EQ(result.rate_limited, 0);
  EXPECT_EQ(result.effort_limited, 1);
  expectJoints(torque, {10.0});
}

TEST(TorqueShaper, RateLimitActsOnTheFilteredTorqueAndKeepsTheFilterState) {
  // alpha 0.5, step 2. Cycle 1: filtered 0.5 * 8 = 4, sent 2. Cycle 2 with 0: the filter
  // continues from 4 (its own state), giving 2; from the sent 2 it would have given 1.
  TorqueShaper shaper(limits(0.5, joints({2000.0}), joints({kInactive})));
  JointVector torque = joints({8.0});
  EXPECT_EQ(shaper.apply(torque, kPeriod).rate_limited, 1);
  expectJoints(torque, {2.0});
  torque = joints({0.0});
  EXPECT_EQ(shaper.apply(torque, kPeriod).rate_limited, 0);
  expectJoints(torque, {2.0});
}

TEST(TorqueShaper, CountersAreReportedPerCycle) {
  TorqueShaper shaper(limits(1.0, joints({1000.0, 1000.0}), joints({0.5, 0.5})));
  JointVector torque = joints({5.0, 5.0});
  const ShapingResult limited = shaper.apply(torque, kPeriod);
  EXPECT_EQ(limited.rate_limited, 2);
  EXPECT_EQ(limited.effort_limited, 2);
  torque = joints({0.25, 0.5});
  const ShapingResult free = shaper.apply(torque, kPeriod);
  EXPECT_EQ(free.rate_limited, 0);
  EXPECT_EQ(free.effort_limited, 0);
  expectJoints(torque, {0.25, 0.5});
}

TEST(TorqueShaper, ResetRestartsFilterAndRateLimitFromTheGivenTorque) {
  TorqueShaper shaper(limits(0.5, joints({1000.0, 1000.0}), JointVector::Constant(2, kInactive)));
  JointVector torque = joints({-30.0, 30.0});
  for (int cycle = 0; cycle < 5; ++cycle) {
    shaper.apply(torque, kPeriod);
  }
  shaper.reset(joints({3.0, -3.0}));
  expectJoints(shaper.lastOutput(), {3.0, -3.0});
  // Filter from the reset value: 0.5 * 4 + 0.5 * 3 = 3.5 (within one step of 3);
  // 0.5 * (-6) + 0.5 * (-3) = -4.5, one step from -3 allows -4.
  torque = joints({4.0, -6.0});
  const ShapingResult result = shaper.apply(torque, kPeriod);
  EXPECT_EQ(result.rate_limited, 1);
  expectJoints(torque, {3.5, -4.0});
}

}  // namespace
}  // namespace comply::pipeline
