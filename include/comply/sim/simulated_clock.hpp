#pragma once
// The simulation's time as a control loop's clock: waiting for the next cycle advances the plant
// until then, so hardware::ControlLoop runs a simulation exactly as it runs a robot. With
// `pace_to_wall_clock` it also sleeps so that simulated time keeps up with real time, no faster
// (for --realtime and the interactive viewer).

#include <chrono>

#include "comply/hardware/loop_clock.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::sim {

class SimulatedClock final : public hardware::LoopClock {
 public:
  explicit SimulatedClock(SimulatedRobot& robot, bool pace_to_wall_clock = false);

  [[nodiscard]] double now() noexcept override { return robot_.simTime() - origin_s_; }
  /// Steps the plant (one control period per step) until now() >= time_s.
  void waitUntil(double time_s) noexcept override;

 private:
  SimulatedRobot& robot_;
  bool pace_;
  double origin_s_;
  std::chrono::steady_clock::time_point wall_start_;
};

}  // namespace comply::sim
