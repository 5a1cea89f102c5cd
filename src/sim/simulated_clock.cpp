#include "comply/sim/simulated_clock.hpp"

#include <thread>

namespace comply::sim {

namespace {

using SteadyClock = std::chrono::steady_clock;

/// How far behind the wall clock a viewer's pacing may fall before it starts again from now.
constexpr auto kViewerCatchUpLimit = std::chrono::milliseconds(50);

SteadyClock::duration steadyDuration(double seconds) {
  return std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

SimulatedClock::SimulatedClock(SimulatedRobot& robot, bool pace_to_wall_clock)
    : robot_(robot), pace_(pace_to_wall_clock), origin_s_(robot.simTime()) {}

void SimulatedClock::waitUntil(double time_s) noexcept {
  const bool pace = pacing();
  if (pace && anchored_ && !pace_ &&
      SteadyClock::now() - (wall_start_ + steadyDuration(now())) > kViewerCatchUpLimit) {
    // Paced for a viewer only: time spent outside the loop (a Python policy thinking, a
    // breakpoint) is not made up by running fast afterwards, which a viewer would see.
    anchored_ = false;
  }
  if (pace && !anchored_) {
    wall_start_ = SteadyClock::now() - steadyDuration(now());
    anchored_ = true;
  } else if (!pace) {
    anchored_ = false;  // paced again later: from then on, not making up the unpaced stretch
  }
  // Half a period of slack: floating-point sums of the period must not skip or add a step.
  const double tolerance_s = 0.5 * robot_.controlPeriod();
  while (now() < time_s - tolerance_s) {
    robot_.step();
  }
  if (pace) {
    std::this_thread::sleep_until(wall_start_ + steadyDuration(now()));
  }
}

double SimulatedClock::lateness(double time_s) noexcept {
  if (!pacing() || !anchored_) {
    return now() - time_s;
  }
  return std::chrono::duration<double>(SteadyClock::now() - wall_start_).count() - time_s;
}

}  // namespace comply::sim
