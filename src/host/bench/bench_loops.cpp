// The timed loops of `comply bench` (see bench_loops.hpp).

#include "bench_loops.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace comply::host::bench {
namespace {

using Clock = std::chrono::steady_clock;

// How long before a paced cycle the loop wakes to warm the caches (row paced_warm) [s].
constexpr double kWarmAheadS = 50e-6;

double microseconds(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::micro>(end - start).count();
}

/// A smooth motion around home: every joint swings 0.1 rad at its own frequency, so each cycle
/// sees a new configuration (as on a robot) and caches/branches are not trained on one input.
JointState stateAt(const std::vector<double>& home, int cycle) {
  const auto dof = static_cast<int>(home.size());
  JointState state = JointState::zero(dof);
  const double t = cycle * kPeriodS;
  for (int i = 0; i < dof; ++i) {
    const double omega = 2.0 * M_PI * (0.3 + 0.1 * i);
    state.position[i] = home[i] + 0.1 * std::sin(omega * t + i);
    state.velocity[i] = 0.1 * omega * std::cos(omega * t + i);
  }
  return state;
}

/// The wall clock, waited for by spinning: the pace of a robot without the sleep, so that what
/// the sleep costs the next cycle (caches, predictors, TLB given to others) shows apart.
class SpinningWallClock final : public hardware::LoopClock {
 public:
  [[nodiscard]] double now() noexcept override {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }
  void waitUntil(double time_s) noexcept override {
    while (now() < time_s) {
    }
  }

 private:
  Clock::time_point start_ = Clock::now();
};

/// The cycle of `wrapper` paced at `hz` on `clock` for `cycles` cycles: its controller times [us]
/// after `warmup` cycles.
template <typename Command>
std::vector<double> pacedCycles(pipeline::Wrapper<Command>& wrapper,
                                const std::vector<double>& home, hardware::LoopClock& clock,
                                double hz, int cycles, int warmup, double warm_ahead_s = 0.0) {
  std::vector<double> cycle_us;
  cycle_us.reserve(static_cast<std::size_t>(cycles));
  ReplayHardware replay(home, cycles);
  wrapper.activate(replay.at(0));
  hardware::ControlLoop loop(replay, wrapper, clock,
                             {.period_s = 1.0 / hz,
                              .cycles = static_cast<std::uint64_t>(cycles),
                              .warm_ahead_s = warm_ahead_s});
  CycleTimer timer(warmup, cycle_us);
  loop.setObserver(&timer);
  loop.run();
  return cycle_us;
}

}  // namespace

ReplayHardware::ReplayHardware(const std::vector<double>& home, int cycles) {
  states_.reserve(static_cast<std::size_t>(cycles));
  for (int cycle = 0; cycle < cycles; ++cycle) {
    states_.push_back(stateAt(home, cycle));
  }
}

template <typename Command>
FullCycles<Command>::FullCycles(pipeline::Wrapper<Command>& wrapper, ReplayHardware& replay,
                                int total, int warmup, std::vector<double>& cycle_us)
    : wrapper_(wrapper),
      warmup_(warmup),
      cycle_us_(cycle_us),
      loop_(replay, wrapper, clock_,
            {.period_s = kPeriodS, .cycles = static_cast<std::uint64_t>(total)}),
      timer_(warmup, cycle_us) {
  loop_.setObserver(&timer_);
}

template <typename Command>
void FullCycles<Command>::record(const std::string& wrapper_name) {
  recording_ = std::make_unique<BenchRecording<Command>>(
      warmup_, wrapper_,
      std::filesystem::temp_directory_path() /
          ("comply_bench_" + std::to_string(getpid()) + "_" + wrapper_name + ".mcap"));
  loop_.setObserver(recording_.get());
}

template <typename Command>
void FullCycles<Command>::run(const std::string& wrapper_name) {
  loop_.run();
  if (recording_) {
    recording_->finish();
    cycle_us_ = std::move(recording_->cycle_us);
  }
  if (wrapper_.diagnostics().state != pipeline::WrapperState::kActive) {
    throw std::runtime_error(wrapper_name +
                             " wrapper left normal operation during the benchmark: " +
                             wrapper_.diagnostics().last_error);
  }
}

void pluginSteps(pipeline::Controller& controller, const ReplayHardware& replay, int total,
                 int warmup, const std::string& wrapper_name, std::vector<double>& step_us) {
  // A step must see a new input every time, as in the cycle (a law that keeps state between
  // cycles, such as a warm-started solver, would look faster on a repeated input).
  comply_output output{};
  for (int cycle = 0; cycle < total; ++cycle) {
    controller.measureOnly(replay.at(cycle));
    const Clock::time_point start = Clock::now();
    const comply_status status = controller.stepPluginOnly(output);
    const Clock::time_point end = Clock::now();
    if (status != COMPLY_OK) {
      throw std::runtime_error(wrapper_name +
                               " plugin failed during the benchmark: " + output.message);
    }
    if (cycle >= warmup) {
      step_us.push_back(microseconds(start, end));
    }
  }
}

template <typename Command>
void appendPacedRows(pipeline::Wrapper<Command>& wrapper, const std::vector<double>& home,
                     const BenchOptions& options, int total, const RowNames& names,
                     std::vector<BenchRow>& rows) {
  // The same cycle as a robot runs it: on the wall clock, the thread asleep between cycles, so
  // that every cycle starts with whatever caches and predictors the sleep left.
  const int paced = std::min(total, static_cast<int>(3.0 * options.paced_hz));
  const int paced_warmup = std::min(options.warmup, paced / 10);
  hardware::WallClock wall;
  std::vector<double> paced_us =
      pacedCycles(wrapper, home, wall, options.paced_hz, paced, paced_warmup);
  rows.push_back(benchRow(names, "paced_cycle", paced_us));
  // The same pace without the sleep: the difference is what sleeping costs the next cycle.
  SpinningWallClock spinning;
  std::vector<double> spin_us =
      pacedCycles(wrapper, home, spinning, options.paced_hz, paced, paced_warmup);
  rows.push_back(benchRow(names, "paced_spin", spin_us));
  // Asleep, but woken early to warm the caches and spin to the start (LoopOptions::warm_ahead_s).
  std::vector<double> warm_us =
      pacedCycles(wrapper, home, wall, options.paced_hz, paced, paced_warmup, kWarmAheadS);
  rows.push_back(benchRow(names, "paced_warm", warm_us));
}

template class FullCycles<JointCommand>;
template class FullCycles<CartesianCommand>;
template void appendPacedRows(pipeline::Wrapper<JointCommand>&, const std::vector<double>&,
                              const BenchOptions&, int, const RowNames&, std::vector<BenchRow>&);
template void appendPacedRows(pipeline::Wrapper<CartesianCommand>&, const std::vector<double>&,
                              const BenchOptions&, int, const RowNames&, std::vector<BenchRow>&);

}  // namespace comply::host::bench
