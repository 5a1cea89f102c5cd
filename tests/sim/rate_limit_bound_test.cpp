// The gain bound's torque-rate part (pipeline/gain_bound.hpp) on the simulated FR3 and UR5e: the
// torque-rate limit turns a linearly stable loop into a limit cycle once a swing of the law's
// torque exceeds about kappa R / w_n, so w_n is held to R / tau (tau = 5 N m). A turn of the
// wrist at 0.95 of that bound passes twice the swing and settles; three times the bound (inside
// the sampled loop's bound, which took it before) is refused, and with the rate part off the same
// turn locks the wrist into a limit cycle at the rate limit, which the same turn without a rate
// limit does not (the limit, not the gain alone, makes it). Every robot and axis:
// rate_limit_sweep_test.cpp (`long`).

#include <gtest/gtest.h>

#include <string>

#include "sim_support.hpp"
#include "turn_step.hpp"

namespace comply::testing {
namespace {

class RateLimitBoundOn : public ::testing::TestWithParam<std::string> {};

TEST_P(RateLimitBoundOn, AGainInsideTheBoundPassesTwiceTheSwingAndSettles) {
  const pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  const pipeline::GainBound& bound = pipeline::resolveController(config)->gain_bound;
  const double tau = bound.rate_limit_swing_nm;
  const double stiffness = 0.95 * rotationalRateBound(bound);
  const TurnOutcome turn = stepTurn(config, stiffness, 2.0 * tau / stiffness, 2);
  ASSERT_TRUE(turn.accepted) << turn.refusal;
  EXPECT_FALSE(turn.faulted);
  EXPECT_EQ(turn.late_hits, 0U);
  EXPECT_LT(turn.late_ripple_nm, 0.5);
}

TEST_P(RateLimitBoundOn, AGainOutsideIsRefusedAndWouldLockIntoALimitCycle) {
  pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  const pipeline::GainBound bound = pipeline::resolveController(config)->gain_bound;
  const double tau = bound.rate_limit_swing_nm;
  const double stiffness = 3.0 * rotationalRateBound(bound);
  ASSERT_LT(stiffness, rotationalSampledBound(bound));             // what the bound took before
  const double step_rad = 2.0 * tau / rotationalRateBound(bound);  // a swing of 6 tau
  const TurnOutcome refused = stepTurn(config, stiffness, step_rad, 2);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.refusal.find("torque-rate limit"), std::string::npos) << refused.refusal;

  config.validation.rate_limit_swing_nm = 0.0;  // the rate part off: the sampled bound takes it
  const TurnOutcome chatter = stepTurn(config, stiffness, step_rad, 2);
  ASSERT_TRUE(chatter.accepted) << chatter.refusal;
  // Every cycle of the last 0.5 s at the rate limit on some joint, or a FAULT that ended it.
  EXPECT_TRUE(chatter.faulted || chatter.late_hits > 400U)
      << chatter.late_hits << " hits, ripple " << chatter.late_ripple_nm << " N m";

  config.torque_rate_limit.assign(static_cast<std::size_t>(config.dof), 1e9);  // no rate limit
  const TurnOutcome unlimited = stepTurn(config, stiffness, step_rad, 2);
  ASSERT_TRUE(unlimited.accepted) << unlimited.refusal;
  EXPECT_FALSE(unlimited.faulted);
  EXPECT_LT(unlimited.late_ripple_nm, 0.5);
}

INSTANTIATE_TEST_SUITE_P(FrankaAndUr, RateLimitBoundOn, ::testing::Values("fr3", "ur5e"));

}  // namespace
}  // namespace comply::testing
