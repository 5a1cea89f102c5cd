#pragma once
// The simulation's time as a control loop's clock: waiting for the next cycle advances the plant
// until then, so hardware::ControlLoop runs a simulation exactly as it runs a robot. With
// `pace_to_wall_clock` it also sleeps so that simulated time keeps up with real time, no faster
// (`comply run --sim`, --realtime and the interactive viewer), from the first wait on: the time a
// host takes to set up before its first cycle is not a backlog the plant then runs through.

#include <atomic>
#include <chrono>

#include "comply/hardware/loop_clock.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::sim {

class SimulatedClock final : public hardware::LoopClock {
 public:
  explicit SimulatedClock(SimulatedRobot& robot, bool pace_to_wall_clock = false);

  [[nodiscard]] double now() noexcept override { return robot_.simTime() - origin_s_; }
  /// Steps the plant (one control period per step) until now() >= time_s; paced, then sleeps
  /// until time_s's real-time deadline.
  void waitUntil(double time_s) noexcept override;
  /// Paced: how far the wall clock is past time_s's real-time deadline, so that a stalled host
  /// shows as late while the plant, stepped back to back, catches up; else now() - time_s.
  [[nodiscard]] double lateness(double time_s) noexcept override;
  /// Also paces while `*flag` is set (a viewer watching `comply sim`), re-anchored each time it
  /// becomes set and whenever the wall clock got more than 50 ms ahead (the caller away between
  /// waits: a viewer sees no fast-forward); the run goes as fast as it can between. Not owned;
  /// nullptr: only the constructor's choice.
  void paceWhile(const std::atomic<bool>* flag) noexcept { pace_while_ = flag; }

 private:
  SimulatedRobot& robot_;
  [[nodiscard]] bool pacing() const noexcept {
    return pace_ || (pace_while_ != nullptr && pace_while_->load(std::memory_order_relaxed));
  }

  bool pace_;
  const std::atomic<bool>* pace_while_ = nullptr;
  double origin_s_;
  bool anchored_ = false;
  /// Paced: the wall-clock time at which now() read 0 (set by the first waitUntil()).
  std::chrono::steady_clock::time_point wall_start_;
};

}  // namespace comply::sim
