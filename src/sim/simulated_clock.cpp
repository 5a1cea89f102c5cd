#include "comply/sim/simulated_clock.hpp"

#include <thread>

namespace comply::sim {

SimulatedClock::SimulatedClock(SimulatedRobot& robot, bool pace_to_wall_clock)
    : robot_(robot),
      pace_(pace_to_wall_clock),
      origin_s_(robot.simTime()),
      wall_start_(std::chrono::steady_clock::now()) {}

void SimulatedClock::waitUntil(double time_s) noexcept {
  // Half a period of slack: floating-point sums of the period must not skip or add a step.
  const double tolerance_s = 0.5 * robot_.controlPeriod();
  while (now() < time_s - tolerance_s) {
    robot_.step();
  }
  if (pace_) {
    std::this_thread::sleep_until(wall_start_ +
                                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(now())));
  }
}

}  // namespace comply::sim
