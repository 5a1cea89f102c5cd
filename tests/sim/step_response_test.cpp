// A 3 cm step of the Cartesian reference on the simulated FR3: the impedance settles without
// sustained oscillation, and the torque-rate limit holds on every joint in every cycle (read from
// the log, not from the wrapper's own counters).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "comply/host/sim_session.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

TEST(StepResponse, SettlesWithoutSustainedOscillationWithinTheTorqueRateLimit) {
  host::SimRunOptions run = fr3ExampleRun("step_response.yaml");
  const host::SimResult result = host::runSimulation(run);
  const host::SimLog& log = result.log;
  ASSERT_EQ(result.summary.faults, 0U);
  ASSERT_EQ(result.summary.rejections, 0U);
  ASSERT_GT(log.size(), 2500U);
  // The controller's cost is kept for every cycle and summarised (how large it is belongs to
  // `comply bench`, not to a test on a shared machine).
  ASSERT_EQ(log.cycle_cost_us.size(), log.size());
  EXPECT_GT(result.summary.cycle_cost.p50_us, 0.0);
  EXPECT_LE(result.summary.cycle_cost.p50_us, result.summary.cycle_cost.p99_us);

  // The step is there: 30 mm of error right after it.
  const auto step_row = static_cast<std::size_t>(0.5 / 0.001) + 1;
  EXPECT_GT(log.positionError(step_row), 0.029);

  // Rate limit from the log: |tau(k) - tau(k-1)| / dt <= limit on every joint.
  const double limit = run.config.torque_rate_limit.front();
  double max_rate = 0.0;
  for (std::size_t row = 1; row < log.size(); ++row) {
    const double dt = log.time_s[row] - log.time_s[row - 1];
    max_rate =
        std::max(max_rate, (log.torque[row] - log.torque[row - 1]).cwiseAbs().maxCoeff() / dt);
  }
  EXPECT_LE(max_rate, limit * (1.0 + 1e-9));
  EXPECT_GT(max_rate, 0.5 * limit) << "the step should have pushed the torque rate to its limit";

  // Settled: within 2 mm at the end, and the last second is quiet: the error neither grows nor
  // swings (peak-to-peak below 0.5 mm), and the TCP speed is small.
  EXPECT_LT(log.positionError(log.size() - 1), 0.002);
  const std::size_t last_second = log.size() - 1000;
  double low = 1.0;
  double high = 0.0;
  for (std::size_t row = last_second; row < log.size(); ++row) {
    low = std::min(low, log.positionError(row));
    high = std::max(high, log.positionError(row));
  }
  EXPECT_LT(high - low, 5e-4);
  const double speed =
      (log.tcp_position.back() - log.tcp_position[log.size() - 11]).norm() / (10 * 0.001);
  EXPECT_LT(speed, 1e-3);
  // The first overshoot beyond the target is small for a critically damped law.
  double overshoot = 0.0;
  const double target_x = log.reference_position.back().x();
  for (std::size_t row = step_row; row < log.size(); ++row) {
    overshoot = std::max(overshoot, log.tcp_position[row].x() - target_x);
  }
  EXPECT_LT(overshoot, 0.2 * 0.03);
}

}  // namespace
}  // namespace comply::testing
