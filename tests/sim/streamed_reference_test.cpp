// The README's first run, examples/sim/press_on_table.yaml, through its first 2 s: the TCP moves
// and turns over the table in free space. The task streams its reference at the control rate, so
// the wrist turns smoothly: almost no cycle meets the torque-rate limit (the few that do are the
// activation and the reference's start). Streamed at 100 Hz, the same motion is a staircase the
// cycle holds between commands: each 10 ms step of the orientation (0.23 deg) asks
// 300 N m/rad x 3.9 mrad = 1.2 N m of joints 1, 3 and 7 at once, more than the limit's 1 N m a
// cycle, a 100 Hz sawtooth of about 0.8 N m on those joints and 0.1 to 0.9 deg of orientation
// error.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "comply/host/sim_session.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// The largest change of a joint's torque from one cycle to the next after `from_s` [N m].
double largestTorqueStep(const host::SimLog& log, int joint, double from_s) {
  double largest = 0.0;
  for (std::size_t i = 1; i < log.size(); ++i) {
    if (log.time_s[i] >= from_s) {
      largest = std::max(largest, std::abs(log.torque[i][joint] - log.torque[i - 1][joint]));
    }
  }
  return largest;
}

host::SimResult pressFreeMotion(double command_rate_hz) {
  host::SimRunOptions run = fr3ExampleRun("press_on_table.yaml");
  run.task.command_rate_hz = command_rate_hz;
  run.duration_s = 2.0;  // the approach, before the probe touches the table
  // A folder per rate: ctest may run both tests at once.
  run.out_dir = std::filesystem::temp_directory_path() /
                ("comply_streamed_reference_" + std::to_string(static_cast<int>(command_rate_hz)));
  run.snapshots = false;
  return host::runSimulation(run);
}

TEST(StreamedReference, TheReadmeRunTurnsItsWristWithoutMeetingTheTorqueRateLimit) {
  const host::SimResult result =
      pressFreeMotion(fr3ExampleRun("press_on_table.yaml").task.command_rate_hz);
  ASSERT_EQ(result.summary.faults, 0U);
  ASSERT_EQ(result.summary.rejections, 0U);
  EXPECT_LE(result.summary.rate_limit_hits, 20U);  // 635 when the example streamed at 100 Hz
  // Past the start, the wrist's torque moves by a small part of the limit's 1 N m a cycle.
  EXPECT_LT(largestTorqueStep(result.log, 6, 0.1), 0.25);  // 0.12 N m; 1.0 at 100 Hz
}

TEST(StreamedReference, AReferenceStreamedAt100HzStepsTheWristTorqueAtTheLimit) {
  const host::SimResult result = pressFreeMotion(100.0);
  ASSERT_EQ(result.summary.faults, 0U);
  EXPECT_GT(result.summary.rate_limit_hits, 400U);
  EXPECT_GT(largestTorqueStep(result.log, 6, 0.1), 0.99);  // the full 1 N m a cycle
}

}  // namespace
}  // namespace comply::testing
