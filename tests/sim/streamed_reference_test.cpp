// The README's first run, examples/sim/press_on_table.yaml, through its first 2 s: the TCP moves
// and turns over the table in free space. The task streams its reference at the control rate, and
// it starts and ends at rest (interpolate: smooth), so the wrist turns smoothly: no cycle meets
// the torque-rate limit. Before, 17 did: the linear reference's velocity stepped at its start and
// its end, and the law's damping with it (designed on an arm without its rotors, it also left
// the wrist ringing at 10 Hz after each waypoint). Streamed at 100 Hz, the same motion is a
// staircase the cycle holds between commands: each 10 ms step of the orientation asks more of
// joints 1, 3 and 7 at once than the limit's 1 N m a cycle, a 100 Hz sawtooth on those joints.

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
  EXPECT_EQ(result.summary.rate_limit_hits, 0U);  // 17 with a linear reference; 635 at 100 Hz
  // The wrist's torque moves by a small part of the limit's 1 N m a cycle.
  EXPECT_LT(largestTorqueStep(result.log, 6, 0.0), 0.25);
}

/// How often the orientation error turns back by more than `amplitude_rad`: a ring's half cycles.
int orientationReversals(const host::SimLog& log, double amplitude_rad) {
  int reversals = 0;
  int direction = 0;
  double extreme = log.orientationError(0);
  for (std::size_t i = 1; i < log.size(); ++i) {
    const double error = log.orientationError(i);
    if (direction >= 0 && error > extreme) {
      extreme = error;
      direction = 1;
    } else if (direction <= 0 && error < extreme) {
      extreme = error;
      direction = -1;
    } else if (std::abs(error - extreme) > amplitude_rad) {
      ++reversals;
      direction = -direction;
      extreme = error;
    }
  }
  return reversals;
}

TEST(StreamedReference, TheWholeReadmeRunNeitherMeetsTheRateLimitNorRings) {
  host::SimRunOptions run = fr3ExampleRun("press_on_table.yaml");
  run.snapshots = false;
  const host::SimResult result = host::runSimulation(run);
  ASSERT_EQ(result.summary.faults, 0U);
  EXPECT_EQ(result.summary.rate_limit_hits, 0U);
  // 34 turns of more than 0.02 deg with the linear reference and the law's M without the rotors
  // (the 10 Hz ring after each waypoint); what is left is the turn itself and the touch-down.
  EXPECT_LE(orientationReversals(result.log, 0.02 * M_PI / 180.0), 8);
}

TEST(StreamedReference, AReferenceStreamedAt100HzStepsTheWristTorqueAtTheLimit) {
  const host::SimResult result = pressFreeMotion(100.0);
  ASSERT_EQ(result.summary.faults, 0U);
  EXPECT_GT(result.summary.rate_limit_hits, 200U);
  EXPECT_GT(largestTorqueStep(result.log, 6, 0.1), 0.99);  // the full 1 N m a cycle
}

}  // namespace
}  // namespace comply::testing
