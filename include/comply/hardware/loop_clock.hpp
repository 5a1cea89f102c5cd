#pragma once
// The time base of a control loop. A wall clock sleeps until each cycle's start; a simulated
// clock advances the simulation until then (sim/simulated_clock.hpp), so the same loop runs in
// real time on a robot and as fast as possible in a simulation.

namespace comply::hardware {

/// CLOCK_MONOTONIC in seconds: what every loop clock and cycle timestamp is measured on.
double monotonicSeconds() noexcept;

class LoopClock {
 public:
  virtual ~LoopClock() = default;
  /// Current time [s] on this clock.
  [[nodiscard]] virtual double now() noexcept = 0;
  /// Returns once now() >= `time_s` (at once when that has passed).
  virtual void waitUntil(double time_s) noexcept = 0;
  /// True when time passes by itself (a wall clock): a loop may then spin until a time.
  [[nodiscard]] virtual bool passesByItself() const noexcept { return false; }
  /// How late [s] it is now for `time_s` on this clock. A clock kept to real time (the wall
  /// clock; a simulation paced to it) says it on the wall clock, so a stall of the thread shows
  /// however the time of the clock itself goes on; one that is not (a simulation run as fast as
  /// it can) on its own time: now() - time_s.
  [[nodiscard]] virtual double lateness(double time_s) noexcept { return now() - time_s; }
};

/// The monotonic wall clock; waitUntil() sleeps with an absolute deadline (no drift).
class WallClock final : public LoopClock {
 public:
  WallClock();
  [[nodiscard]] double now() noexcept override;
  void waitUntil(double time_s) noexcept override;
  [[nodiscard]] bool passesByItself() const noexcept override { return true; }

 private:
  double origin_s_ = 0.0;
};

/// A clock that is always "now": the loop runs back to back (benchmarks, replays).
class FreeRunningClock final : public LoopClock {
 public:
  [[nodiscard]] double now() noexcept override { return now_s_; }
  void waitUntil(double time_s) noexcept override {
    if (time_s > now_s_) {
      now_s_ = time_s;
    }
  }

 private:
  double now_s_ = 0.0;
};

}  // namespace comply::hardware
