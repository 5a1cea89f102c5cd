// Timed chunks on the simulated FR3 (experiments/chunks): a policy's chunks arriving at 10, 15
// and 30 Hz, each one taking over from the one before while the arm moves, keep the reference C1
// and the torque smooth enough that the torque-rate limiter never engages; the same circle from
// stepped setpoints at 15 Hz does engage it (so the measures can fail) and tracks worse.

#include <gtest/gtest.h>

#include <sstream>

#include "chunks/chunk_experiment.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

// The controller file's torque-rate limit [N m/s per joint].
constexpr double kTorqueRateLimit = 1000.0;
// Velocity continuity of the reference: its finite-difference velocity changes by at most this
// much from one 1 ms cycle to the next [m/s], an acceleration of 20 m/s^2. A step of a setpoint
// 1 cm away moves it by 10 m/s at once.
constexpr double kVelocityStepTolerance = 0.02;

TEST(ChunkPreemption, ChunksAtTenFifteenAndThirtyHertzKeepTheReferenceC1AndTheLimiterIdle) {
  std::ostringstream progress;
  auto options = freshExperiment<experiments::ChunkOptions>("comply_chunk_test", progress);
  options.settings.duration_s = 3.0;
  options.pictures = false;
  options.conditions = {"stepped_15hz", "chunks_10hz", "chunks_15hz", "chunks_30hz"};
  const std::vector<experiments::ChunkRow> rows = experiments::runChunks(options);
  ASSERT_EQ(rows.size(), 4U);
  const experiments::chunks::RunResult& stepped = rows[0].result;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const experiments::chunks::RunResult& chunked = rows[i].result;
    SCOPED_TRACE(rows[i].condition.name);
    EXPECT_GT(chunked.actions, 20U);
    EXPECT_EQ(chunked.faults, 0U);
    EXPECT_EQ(chunked.rate_limit_hits, 0U);
    EXPECT_LT(chunked.max_torque_rate_nm_per_s, 0.8 * kTorqueRateLimit);
    EXPECT_LT(chunked.max_reference_velocity_step, kVelocityStepTolerance);
    EXPECT_LT(chunked.rmse_mm, 0.5 * stepped.rmse_mm);
  }
  EXPECT_GT(stepped.rate_limit_hits, 0U);
  EXPECT_GT(stepped.max_reference_velocity_step, 50 * kVelocityStepTolerance);
}

TEST(ChunkPreemption, AnUnknownConditionIsRefusedBeforeAnyRun) {
  EXPECT_THROW(experiments::chunkConditionOf("chunks_fast"), std::invalid_argument);
  EXPECT_THROW(experiments::chunkConditionOf("stepped_0hz"), std::invalid_argument);
  const experiments::chunks::Condition condition = experiments::chunkConditionOf("chunks_12.5hz");
  EXPECT_EQ(condition.mode, experiments::chunks::Mode::kChunks);
  EXPECT_DOUBLE_EQ(condition.rate_hz, 12.5);
}

}  // namespace
}  // namespace comply::testing
