#pragma once
// The control loop every host runs: wait for the cycle's start on a clock, read the hardware, run
// the controller, write the torque, tell an observer. The simulator, `comply bench`,
// `comply validate --wrapper` and live hosts differ only in the hardware, the clock and the
// observer they plug in.
//
//   ControlLoop loop(hardware, controller, clock, {.period_s = 0.001, .cycles = 5000});
//   loop.setObserver(&logger);
//   const LoopStats stats = loop.run();
//
// run() itself never allocates; whether a cycle is real-time safe depends on what is plugged in
// (the wrappers and SimulatedRobot are; an observer that logs to a vector is not).

#include <atomic>
#include <cstdint>
#include <span>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/hardware/hardware_interface.hpp"
#include "comply/hardware/loop_clock.hpp"

namespace comply::hardware {

/// The controller as the loop sees it (the joint and Cartesian wrappers implement it).
class CycleController {
 public:
  virtual ~CycleController() = default;
  [[nodiscard]] virtual int dof() const noexcept = 0;
  /// The kind of command cycle() writes (fixed for the controller's life).
  [[nodiscard]] virtual OutputMode outputMode() const noexcept { return OutputMode::kTorque; }
  /// One control cycle at `state`; true when `command` (sized for dof(), in outputMode()) holds a
  /// command to write.
  virtual bool cycle(const JointState& state, double period_s,
                     ActuatorCommand& command) noexcept = 0;
  /// After a cycle that wrote: the controller cannot trust the state it holds the arm at (a
  /// frozen sensor stream), so the hardware should hold it as well, with its brakes or its own
  /// position hold (HardwareInterface::hold), where it has them.
  [[nodiscard]] virtual bool wantsHold() const noexcept { return false; }
  /// The contact the controller's own contact handling lets through now, largest force [N] and
  /// torque [N m] (its reflex thresholds in force); false when it has none. Passed on to the
  /// hardware after every cycle (HardwareInterface::allowContact).
  virtual bool contactAllowance(double& force_n, double& torque_n_m) const noexcept {
    (void)force_n;
    (void)torque_n_m;
    return false;
  }
  /// Shortly before a cycle that follows a sleep (LoopOptions::warm_ahead_s): bring what the
  /// cycle reads back into the caches, from `last_state` (the state the last cycle read), without
  /// changing anything the next cycle computes. Real-time.
  virtual void warm(const JointState& last_state) noexcept { (void)last_state; }
};

/// What the observer learns about one cycle.
struct CycleRecord {
  std::uint64_t index = 0;  ///< 0 for the first cycle
  double time_s = 0.0;      ///< scheduled start on the loop's clock [s]
  double period_s = 0.0;    ///< nominal period [s]
  /// Actual start minus scheduled start [s]: on the wall clock where the loop's clock keeps to
  /// real time, a paced simulation's too (LoopClock::lateness).
  double start_lateness_s = 0;
  double compute_s = 0.0;     ///< wall time from read() to the end of write() [s]
  double controller_s = 0.0;  ///< wall time of the controller's cycle alone [s]
  bool wrote = false;         ///< a torque was written
  bool held = false;          ///< no torque: the hardware held the arm (HardwareInterface::hold)
  /// The cycle ended after its deadline, the next cycle's start: start_lateness_s (when late)
  /// plus compute_s exceeded the period.
  bool overrun = false;
  const JointState* state = nullptr;
  /// The effort of the cycle's command (ActuatorCommand::effort: the torque in torque mode).
  std::span<const double> torque;
  const ActuatorCommand* command = nullptr;  ///< the whole command, in the controller's mode
};

class LoopObserver {
 public:
  virtual ~LoopObserver() = default;
  /// Before the cycle at `time_s` reads the hardware: command sources submit here.
  virtual void beforeCycle(std::uint64_t /*index*/, double /*time_s*/) {}
  /// After the cycle wrote its torque.
  virtual void afterCycle(const CycleRecord& /*record*/) {}
};

struct LoopOptions {
  double period_s = 0.001;   ///< [s], > 0
  std::uint64_t cycles = 0;  ///< run() stops after this many; 0: until stop()
  /// > 0: wake this long [s] before each cycle's start, let the controller warm its caches
  /// (CycleController::warm) and spin to the start. Only on a clock whose time passes by itself
  /// (LoopClock::passesByItself: a robot's); 0: off.
  double warm_ahead_s = 0.0;
};

struct LoopStats {
  std::uint64_t cycles = 0;
  std::uint64_t overruns = 0;        ///< cycles that ended after their deadline (CycleRecord)
  std::uint64_t read_failures = 0;   ///< cycles skipped: the hardware had no valid measurement
  std::uint64_t write_failures = 0;  ///< torques the hardware refused
  std::uint64_t held_cycles = 0;     ///< cycles without controller output, the arm held
  double max_compute_s = 0.0;
  double max_start_lateness_s = 0.0;  ///< CycleRecord::start_lateness_s, the largest [s]
};

class ControlLoop {
 public:
  /// Throws std::invalid_argument when the hardware and the controller disagree on the number of
  /// joints, the hardware does not accept the controller's output mode, or the period is not a
  /// positive finite number.
  ControlLoop(HardwareInterface& hardware, CycleController& controller, LoopClock& clock,
              LoopOptions options);

  void setObserver(LoopObserver* observer) noexcept { observer_ = observer; }

  /// Runs cycles until options.cycles are done or stop() is called.
  LoopStats run();
  /// One cycle at the next scheduled time; false when stop() was called.
  bool runOnce();
  /// Any thread: run() returns after the current cycle.
  void stop() noexcept { stop_requested_.store(true, std::memory_order_relaxed); }

  [[nodiscard]] const LoopStats& stats() const noexcept { return stats_; }
  [[nodiscard]] double period() const noexcept { return options_.period_s; }
  /// The torque of the last cycle that wrote one [N m | N], dof() long (zeros before the first).
  [[nodiscard]] std::span<const double> lastTorque() const noexcept {
    return {command_.effort.data(), static_cast<std::size_t>(command_.effort.size())};
  }
  /// The last cycle's whole command, in the controller's output mode.
  [[nodiscard]] const ActuatorCommand& lastCommand() const noexcept { return command_; }
  /// Scheduled time of the next cycle on the loop's clock [s]; the first cycle's is its clock's
  /// time when it runs.
  [[nodiscard]] double nextCycleTime() const noexcept;

 private:
  HardwareInterface& hardware_;
  CycleController& controller_;
  LoopClock& clock_;
  LoopOptions options_;
  LoopObserver* observer_ = nullptr;
  std::atomic<bool> stop_requested_{false};
  LoopStats stats_;
  std::uint64_t next_index_ = 0;
  double start_s_ = 0.0;
  JointState state_;
  ActuatorCommand command_;
};

}  // namespace comply::hardware
