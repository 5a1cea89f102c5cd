// The gain bound's torque-rate part (pipeline/gain_bound.hpp) on every shipped robot and on a
// Gen3-like 7-DOF arm added by path, about each axis of the TCP: at 0.95 of the bound, turns of
// the orientation reference that ask one, two and four times tau of the wrist settle without a
// cycle at the rate limit (the bound promises one tau; in this simulation, without a driver's
// delay and critically damped, about 3.5 are left, docs/safety.md). Three times the bound,
// refused since, is in rate_limit_bound_test.cpp. A sweep of 45 runs: `make test-all`.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <tuple>

#include "comply/model/robot_description.hpp"
#include "sim_support.hpp"
#include "turn_step.hpp"

namespace comply::testing {
namespace {

std::vector<std::string> robotsAndOneByPath() {
  std::vector<std::string> robots = model::availableRobots();
  robots.push_back((kSourceDir / "tests" / "sim" / "robots" / "gen3like").string());
  return robots;
}

class RateLimitSweep : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(RateLimitSweep, InsideTheBoundTurnsOfUpToFourTauSettle) {
  const auto& [robot, axis] = GetParam();
  const pipeline::WrapperConfig config = simCartesianConfig(robot);
  const pipeline::GainBound bound = pipeline::resolveController(config)->gain_bound;
  const double stiffness = 0.95 * rotationalRateBound(bound);
  for (const double swings : {1.0, 2.0, 4.0}) {
    SCOPED_TRACE(std::to_string(swings) + " tau");
    const TurnOutcome turn =
        stepTurn(config, stiffness, swings * bound.rate_limit_swing_nm / stiffness, axis);
    ASSERT_TRUE(turn.accepted) << turn.refusal;
    EXPECT_FALSE(turn.faulted);
    EXPECT_EQ(turn.late_hits, 0U);
    EXPECT_LT(turn.late_ripple_nm, 0.5);
  }
}

INSTANTIATE_TEST_SUITE_P(
    RobotsAndAxes, RateLimitSweep,
    ::testing::Combine(::testing::ValuesIn(robotsAndOneByPath()), ::testing::Values(0, 1, 2)),
    [](const auto& test) {
      return std::filesystem::path(std::get<0>(test.param)).filename().string() + "_axis" +
             "xyz"[std::get<1>(test.param)];
    });

}  // namespace
}  // namespace comply::testing
