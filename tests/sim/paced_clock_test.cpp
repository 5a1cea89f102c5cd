// A simulation paced to the wall clock (`comply run --sim`) keeps real-time deadlines: a stall of
// the host's thread is lateness and overruns on the wall clock, while the plant, stepped back to
// back, catches up on its own time. Measured on the simulation's time, as it once was, a 15 ms
// stall read as on time. Run as fast as it can (`comply sim`), a simulation has no such deadline.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "comply/hardware/control_loop.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "sim_support.hpp"
#include "stalling_observer.hpp"

namespace comply::testing {
namespace {

constexpr std::uint64_t kStallAfter = 10;
constexpr std::uint64_t kCycles = 30;

struct StalledRun {
  testing::StallingObserver observer{kStallAfter};
  hardware::LoopStats stats;
};

StalledRun runWithAStall(bool paced) {
  const pipeline::WrapperConfig config = simCartesianConfig("fr3");
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  sim::SimulatedClock clock(plant, paced);
  pipeline::CartesianWrapper wrapper(config);
  JointState state = JointState::zero(plant.dof());
  plant.read(state);
  wrapper.activate(state);
  hardware::ControlLoop loop(plant, wrapper, clock,
                             {.period_s = plant.controlPeriod(), .cycles = kCycles});
  StalledRun run;
  loop.setObserver(&run.observer);
  run.stats = loop.run();
  return run;
}

TEST(PacedSimulation, AStallOfTheHostIsLateOnTheWallClock) {
  const StalledRun run = runWithAStall(true);
  ASSERT_EQ(run.observer.lateness_s.size(), kCycles);
  // The cycle after the stall was due 1 ms after the one before began, and began 15 ms or more
  // after it (a sleep never returns early).
  EXPECT_GE(run.observer.lateness_s[kStallAfter + 1], 0.014);
  EXPECT_TRUE(run.observer.overrun[kStallAfter + 1]);
  EXPECT_GE(run.stats.overruns, 1U);
  EXPECT_GE(run.stats.max_start_lateness_s, 0.014);
}

TEST(PacedSimulation, ASimulationRunAsFastAsItCanIsOnTimeOnItsOwnClock) {
  const StalledRun run = runWithAStall(false);
  ASSERT_EQ(run.observer.lateness_s.size(), kCycles);
  for (const double lateness_s : run.observer.lateness_s) {
    EXPECT_NEAR(lateness_s, 0.0, 1e-9) << "simulated time waits for the host: no deadline";
  }
}

}  // namespace
}  // namespace comply::testing
