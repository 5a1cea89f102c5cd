// Torque shaping seen through the wrapper: a large commanded step reaches the joints no faster than
// the torque-rate limit and never beyond the effort limit, and every clipped joint-cycle is counted
// in the diagnostics.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kTolerance = 1e-9;

TEST(WrapperShaping, TorqueRateLimitSpreadsAStepAndCountsEveryClippedCycle) {
  constexpr double kRateLimit = 50.0;  // N m/s: 0.05 N m per 1 ms cycle
  // The state is held still while the torque ramps for 0.4 s, which is what a stale sensor
  // stream looks like: the frozen-state check is off here, and the gain bound's rate part (the
  // rate limit is far below what the gains need, which is the point).
  JointWrapper wrapper(
      fr3Config(kJointImpedancePlugin, "torque_rate_limit_nm_per_s: " + std::to_string(kRateLimit) +
                                           "\nfrozen_state_timeout_s: 0\n"
                                           "validation: {rate_limit_swing_nm: 0}"));
  const JointVector home = fr3Home();
  const JointState state = restingAt(wrapper.controller(), home);
  wrapper.activate(state);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  ASSERT_EQ(wrapper.diagnostics().rate_limit_hits, 0U) << "holding still needs no clipping";

  // 100 N m/rad x 0.2 rad = 20 N m on joint 1 at once: 400 cycles at 0.05 N m each.
  JointCommand step = JointCommand::zero(kFr3Dof);
  step.stamp_s = 1.0;
  step.fields = CommandField::kPosition;
  step.position = offset(home, 0, 0.2);
  ASSERT_TRUE(wrapper.submit(step).accepted);

  JointVector previous = torque.values;
  for (int cycle = 0; cycle < 500; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    ASSERT_LE(maxDifference(torque.values, previous), kRateLimit * kPeriod * (1.0 + 1e-9))
        << "cycle " << cycle;
    previous = torque.values;
  }
  const JointVector expected = offset(state.effort, 0, 20.0);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, expected, kTolerance);
  const std::uint64_t hits = wrapper.diagnostics().rate_limit_hits;
  EXPECT_GE(hits, 399U);  // the last step may land exactly on the limit without clipping
  EXPECT_LE(hits, 400U);
  EXPECT_EQ(wrapper.diagnostics().effort_limit_hits, 0U);
}

/// 500 N m forward on joint 1 and back on joint 6, far beyond both joints' limits.
JointCommand pushBeyondTheLimits() {
  JointCommand push = JointCommand::zero(kFr3Dof);
  push.stamp_s = 1.0;
  push.fields = CommandField::kTorqueFeedforward;
  push.torque_feedforward[0] = 500.0;
  push.torque_feedforward[5] = -500.0;
  return push;
}

/// A joint wrapper on the FR3 at rest at home, without a rate limit, `pushBeyondTheLimits()` in
/// force; `config_lines`: more of its controller file.
struct Pushed {
  explicit Pushed(const std::string& config_lines = {})
      : wrapper(fr3Config(kJointImpedancePlugin, config_lines + "torque_rate_limit_nm_per_s: " +
                                                     std::to_string(kNoRateLimit))),
        state(restingAt(wrapper.controller(), fr3Home())),
        limit(wrapper.controller().effortLimit()) {
    wrapper.activate(state);
    accepted = wrapper.submit(pushBeyondTheLimits()).accepted;
  }
  JointWrapper wrapper;
  const JointState state;
  const JointVector limit;
  TorqueBuffer torque;
  bool accepted = false;  ///< the wrapper took the push
};

TEST(WrapperShaping, EffortLimitClipsAndCountsEveryClippedCycle) {
  Pushed pushed;
  auto& [wrapper, state, limit, torque, accepted] = pushed;
  ASSERT_TRUE(accepted);
  for (int cycle = 0; cycle < 10; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  EXPECT_EQ(torque.values[0], limit[0]);
  EXPECT_EQ(torque.values[5], -limit[5]);
  EXPECT_NEAR(torque.values[3], state.effort[3], kTolerance) << "other joints unaffected";
  EXPECT_EQ(wrapper.diagnostics().effort_limit_hits, 2U * 10U);
}

// effort_saturation: scale. Clipping joint by joint turned the law's torque (and the wrench it
// commanded) away from what was asked; scaling keeps its direction: the torque above gravity is
// the law's times one share, the joint that binds exactly at its limit.
TEST(WrapperShaping, ScaledSaturationKeepsTheDirectionOfTheLawsTorque) {
  Pushed pushed("effort_saturation: scale\n");
  auto& [wrapper, state, limit, torque, accepted] = pushed;
  ASSERT_TRUE(accepted);
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  const JointVector above_gravity = torque.values - state.effort;  // effort: the gravity torque
  const double share = above_gravity[0] / 500.0;
  EXPECT_GT(share, 0.0);
  EXPECT_LT(share, 1.0);
  EXPECT_NEAR(above_gravity[5], -500.0 * share, 1e-9) << "the direction turned";
  EXPECT_NEAR(std::abs(above_gravity[3]), 0.0, 1e-9);
  const bool joint0_binds = std::abs(std::abs(torque.values[0]) - limit[0]) < 1e-9;
  const bool joint5_binds = std::abs(std::abs(torque.values[5]) - limit[5]) < 1e-9;
  EXPECT_TRUE(joint0_binds || joint5_binds) << torque.values.transpose();
  EXPECT_LE(std::abs(torque.values[0]), limit[0] + 1e-9);
  EXPECT_LE(std::abs(torque.values[5]), limit[5] + 1e-9);
  EXPECT_EQ(wrapper.diagnostics().effort_limit_hits, 1U);
}

}  // namespace
}  // namespace comply::pipeline::test
