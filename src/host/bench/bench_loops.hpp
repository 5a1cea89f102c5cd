#pragma once
// The timed loops of `comply bench` (cycle_bench.hpp) and what they run on: hardware that replays
// a trajectory, the controller's own time of each cycle, the full cycle, the plugin step alone and
// the paced cycle. The control loop times its cycles itself and the plugin step is timed by two
// clock reads around it: nothing here runs inside a timed region but what is timed. Private to
// the host.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bench_recording.hpp"
#include "bench_rows.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/cycle_bench.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::host::bench {

inline constexpr double kPeriodS = 0.001;

/// Hardware that replays the benchmark trajectory, computed before the timed loop so that read()
/// costs a copy; write() accepts everything.
class ReplayHardware final : public hardware::HardwareInterface {
 public:
  ReplayHardware(const std::vector<double>& home, int cycles);
  [[nodiscard]] int dof() const noexcept override {
    return static_cast<int>(states_.front().position.size());
  }
  bool read(JointState& state) noexcept override {
    state = states_[next_++ % states_.size()];
    return true;
  }
  bool write(std::span<const double> /*torque*/) noexcept override { return true; }
  [[nodiscard]] bool accepts(OutputMode /*mode*/) const noexcept override { return true; }
  bool writeCommand(const ActuatorCommand& /*command*/) noexcept override { return true; }
  [[nodiscard]] const JointState& at(int cycle) const {
    return states_[static_cast<std::size_t>(cycle)];
  }

 private:
  std::vector<JointState> states_;
  std::size_t next_ = 0;
};

/// Keeps the controller's own time of every cycle after the warm-up; stops at the first cycle
/// that leaves normal operation.
class CycleTimer final : public hardware::LoopObserver {
 public:
  CycleTimer(int warmup, std::vector<double>& cycle_us) : warmup_(warmup), cycle_us_(cycle_us) {}
  void afterCycle(const hardware::CycleRecord& record) override {
    if (record.index >= static_cast<std::uint64_t>(warmup_)) {
      cycle_us_.push_back(record.controller_s * 1e6);
    }
  }

 private:
  int warmup_;
  std::vector<double>& cycle_us_;
};

/// The full cycle of `wrapper` through the control loop every host runs, on `replay` and the
/// free-running clock for `total` cycles: the controller's times [us] after the warm-up into
/// `cycle_us`, or with a recording its times and the recording's own.
template <typename Command>
class FullCycles {
 public:
  FullCycles(pipeline::Wrapper<Command>& wrapper, ReplayHardware& replay, int total, int warmup,
             std::vector<double>& cycle_us);
  /// Each cycle pushed into a recording's lane as well (Variant::recorded), into a file named
  /// after `wrapper_name` in the temporary folder, removed when done.
  void record(const std::string& wrapper_name);
  /// Runs the cycles; throws when the wrapper left normal operation.
  void run(const std::string& wrapper_name);
  [[nodiscard]] BenchRecording<Command>* recording() const noexcept { return recording_.get(); }

 private:
  pipeline::Wrapper<Command>& wrapper_;
  int warmup_;
  std::vector<double>& cycle_us_;
  hardware::FreeRunningClock clock_;
  hardware::ControlLoop loop_;
  CycleTimer timer_;
  std::unique_ptr<BenchRecording<Command>> recording_;
};

/// The law alone on `replay`'s trajectory for `total` cycles, the model updated untimed before
/// each step: its step times [us] after `warmup` into `step_us`. Throws when a step fails.
void pluginSteps(pipeline::Controller& controller, const ReplayHardware& replay, int total,
                 int warmup, const std::string& wrapper_name, std::vector<double>& step_us);

/// The cycle paced at options.paced_hz on the wall clock, asleep between cycles, spinning
/// instead, and woken early to warm the caches: rows paced_cycle, paced_spin and paced_warm.
template <typename Command>
void appendPacedRows(pipeline::Wrapper<Command>& wrapper, const std::vector<double>& home,
                     const BenchOptions& options, int total, const RowNames& names,
                     std::vector<BenchRow>& rows);

}  // namespace comply::host::bench
