// The cycle's timing protocol (see cycle_bench.hpp).

#include "comply/host/cycle_bench.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "bench_recording.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::host {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kPeriodS = 0.001;
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

/// Hardware that replays the benchmark trajectory, computed before the timed loop so that read()
/// costs a copy; write() accepts everything.
class ReplayHardware final : public hardware::HardwareInterface {
 public:
  ReplayHardware(const std::vector<double>& home, int cycles) {
    states_.reserve(static_cast<std::size_t>(cycles));
    for (int cycle = 0; cycle < cycles; ++cycle) {
      states_.push_back(stateAt(home, cycle));
    }
  }
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

/// What a benchmarked wrapper has on besides its law.
struct Variant {
  DampingMode damping_mode = DampingMode::kRatio;
  bool gain_stage = false;  ///< ramps and energy tank
  bool recorded = false;    ///< the cycle pushed into a recording's lane
  bool observer = false;    ///< the momentum observer
  bool chunked = false;     ///< a timed chunk plays through every cycle
  bool force = false;       ///< a force axis and contact-force limits (with the observer)
  OutputMode output = OutputMode::kTorque;  ///< what the drives take (output.mode)
};

/// A chunk that lasts the whole run: 64 waypoints around the measured TCP, the stiffness and the
/// task frame changing at each, so every cycle evaluates the curve, the gains and the frame.
CartesianChunk benchChunk(const MeasuredPose& measured, double run_s, int dof) {
  CartesianChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kTaskFrame;
  for (int k = 0; k < kMaxChunkWaypoints; ++k) {
    const double t = run_s * k / (kMaxChunkWaypoints - 1);
    ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(dof)};
    waypoint.command.position =
        measured.tcp_position + 0.01 * Eigen::Vector3d(std::sin(k), std::cos(k), 0.0);
    waypoint.command.orientation = measured.tcp_orientation;
    waypoint.command.stiffness_translational = (500.0 + 20.0 * k) * Eigen::Matrix3d::Identity();
    waypoint.command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
    waypoint.command.task_frame =
        Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitZ()) * Eigen::Quaterniond::Identity();
    chunk.waypoints.push_back(waypoint);
  }
  return chunk;
}

template <typename Command>
std::vector<BenchRow> benchWrapper(const BenchOptions& options, const std::string& wrapper_name,
                                   const std::string& plugin_name, const std::vector<double>& home,
                                   std::ostream& log, const Variant& variant = {}) {
  pipeline::WrapperConfig config = host::controllerConfig(options.robot, plugin_name);
  config.initial_cartesian.damping_mode = variant.damping_mode;
  config.observer.enabled = variant.observer || variant.force;
  if (variant.force) {
    config.force_control.contact_force_limit_n = Eigen::Vector3d(30.0, 30.0, 0.0);
  }
  config.output.mode = variant.output;
  if (variant.gain_stage) {
    // Ramps and tank on, the tank far from full so that it refills (and, with ratios, bounds the
    // damping from the mass matrix) every window: the stage's dearest steady state.
    config.gain_ramps.enabled = true;
    config.passivity.enabled = true;
    config.passivity.tank_initial_j = 0.1;
    config.passivity.tank_max_j = 1e6;
  }
  const auto resolved = pipeline::resolveController(config);
  pipeline::Wrapper<Command> wrapper(resolved);
  const int total = options.warmup + options.iterations;
  ReplayHardware replay(home, total);
  wrapper.activate(replay.at(0));
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    if (variant.force) {
      // Force along a turned task frame's z; its x and y under the contact-force limit.
      CartesianCommand command = CartesianCommand::zero(wrapper.dof());
      command.fields = CommandField::kForce | CommandField::kTaskFrame;
      command.task_frame =
          Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::Quaterniond::Identity();
      command.force_axes[2] = 1.0;
      command.wrench_target[2] = 5.0;
      const pipeline::Verdict verdict = wrapper.submit(command);
      if (!verdict.accepted) {
        throw std::runtime_error(wrapper_name +
                                 ": the benchmark's force command was refused: " + verdict.message);
      }
    }
    if (variant.chunked) {
      // The host's clock is the controller's here: 0 at activation.
      const pipeline::Verdict verdict = wrapper.submitChunk(
          benchChunk(wrapper.measuredPose(), 1.5 * total * kPeriodS, wrapper.dof()), 0.0);
      if (!verdict.accepted) {
        throw std::runtime_error(wrapper_name +
                                 ": the benchmark's chunk was refused: " + verdict.message);
      }
    }
  }
  std::vector<double> step_us;
  std::vector<double> cycle_us;
  step_us.reserve(static_cast<std::size_t>(options.iterations));
  cycle_us.reserve(static_cast<std::size_t>(options.iterations));

  // Full cycles first, through the control loop every host runs.
  hardware::FreeRunningClock clock;
  hardware::ControlLoop loop(replay, wrapper, clock,
                             {.period_s = kPeriodS, .cycles = static_cast<std::uint64_t>(total)});
  CycleTimer timer(options.warmup, cycle_us);
  std::unique_ptr<BenchRecording<Command>> recording;
  if (variant.recorded) {
    recording = std::make_unique<BenchRecording<Command>>(
        options.warmup, wrapper,
        std::filesystem::temp_directory_path() /
            ("comply_bench_" + std::to_string(getpid()) + "_" + wrapper_name + ".mcap"));
    loop.setObserver(recording.get());
  } else {
    loop.setObserver(&timer);
  }
  loop.run();
  if (recording) {
    recording->finish();
    cycle_us = std::move(recording->cycle_us);
  }
  if (wrapper.diagnostics().state != pipeline::WrapperState::kActive) {
    throw std::runtime_error(
        wrapper_name +
        " wrapper left normal operation during the benchmark: " + wrapper.diagnostics().last_error);
  }
  // Then the law alone on the same trajectory, with the model updated untimed before each step:
  // a step must see a new input every time, as in the cycle (a law that keeps state between
  // cycles, such as a warm-started solver, would look faster on a repeated input).
  pipeline::Controller& controller = wrapper.controller();
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
    if (cycle >= options.warmup) {
      step_us.push_back(microseconds(start, end));
    }
  }
  log << "  " << wrapper_name << " (" << plugin_name << "): " << options.iterations
      << " cycles done\n";
  const auto row = [&](const char* stage, std::vector<double>& samples) {
    BenchRow result;
    result.wrapper = wrapper_name;
    result.plugin = plugin_name;
    result.stage = stage;
    result.timing = host::summarize(samples);
    result.p50_min_us = result.p50_max_us = result.timing.p50_us;
    return result;
  };
  std::vector<BenchRow> rows{row("plugin_step", step_us), row("full_cycle", cycle_us)};
  if (recording) {
    rows.push_back(row("record_push", recording->push_us));
    std::vector<double> full_us = recording->fullLanePushes(options.warmup, options.iterations);
    rows.push_back(row("record_push_full", full_us));
    rows.push_back(row("state_sample", recording->sample_us));
  }
  if (options.paced_hz > 0.0) {
    // The same cycle as a robot runs it: on the wall clock, the thread asleep between cycles, so
    // that every cycle starts with whatever caches and predictors the sleep left.
    const int paced = std::min(total, static_cast<int>(3.0 * options.paced_hz));
    const int paced_warmup = std::min(options.warmup, paced / 10);
    hardware::WallClock wall;
    std::vector<double> paced_us =
        pacedCycles(wrapper, home, wall, options.paced_hz, paced, paced_warmup);
    rows.push_back(row("paced_cycle", paced_us));
    // The same pace without the sleep: the difference is what sleeping costs the next cycle.
    SpinningWallClock spinning;
    std::vector<double> spin_us =
        pacedCycles(wrapper, home, spinning, options.paced_hz, paced, paced_warmup);
    rows.push_back(row("paced_spin", spin_us));
    // Asleep, but woken early to warm the caches and spin to the start (LoopOptions::warm_ahead_s).
    std::vector<double> warm_us =
        pacedCycles(wrapper, home, wall, options.paced_hz, paced, paced_warmup, kWarmAheadS);
    rows.push_back(row("paced_warm", warm_us));
  }
  return rows;
}

void pinToCpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0) {
    throw std::runtime_error("cannot pin to CPU " + std::to_string(cpu) + ": " +
                             std::strerror(errno));
  }
}

}  // namespace

std::vector<BenchRow> runBench(const BenchOptions& options, std::ostream& log) {
  if (options.iterations < 1 || options.warmup < 0) {
    throw std::runtime_error("--iterations must be >= 1 and --warmup >= 0");
  }
  if (options.cpu >= 0) {
    pinToCpu(options.cpu);
  }
  const model::RobotDescription robot = model::loadRobotDescription(options.robot);
  log << "comply bench: " << robot.name << ", " << options.iterations << " iterations after "
      << options.warmup << " warm-up cycles"
      << (options.cpu >= 0 ? ", pinned to CPU " + std::to_string(options.cpu) : std::string())
      << "\n";
  std::vector<BenchRow> rows;
  const auto add = [&](const std::vector<BenchRow>& wrapper_rows) {
    for (BenchRow row : wrapper_rows) {
      row.robot = robot.name;
      row.dof = static_cast<int>(robot.joints.size());
      rows.push_back(row);
    }
  };
  add(benchWrapper<JointCommand>(options, "joint", "joint_impedance", robot.home, log));
  // Ratio damping (the default) re-derives D from K and the Cartesian inertia every cycle; the
  // absolute mode shows what that costs.
  add(benchWrapper<CartesianCommand>(options, "cartesian", "cartesian_impedance", robot.home, log));
  add(benchWrapper<CartesianCommand>(options, "cartesian_abs", "cartesian_impedance", robot.home,
                                     log, {.damping_mode = DampingMode::kAbsolute}));
  // The same ratio cycle with the gain stage (ramps and energy tank) on.
  add(benchWrapper<CartesianCommand>(options, "cartesian_tank", "cartesian_impedance", robot.home,
                                     log, {.gain_stage = true}));
  // The ratio cycle recorded (comply run --record): the state sample and the push into the
  // recording's lane after each cycle, the writer thread running beside it.
  add(benchWrapper<CartesianCommand>(options, "cartesian_recorded", "cartesian_impedance",
                                     robot.home, log, {.recorded = true}));
  // The ratio cycle with the momentum observer estimating the external wrench.
  add(benchWrapper<CartesianCommand>(options, "cartesian_observer", "cartesian_impedance",
                                     robot.home, log, {.observer = true}));
  // The observer's cycle with force along a task axis and contact-force limits on the others
  // (the force stage: the command in the task frame, the PI, the pull-back).
  add(benchWrapper<CartesianCommand>(options, "cartesian_force", "cartesian_impedance", robot.home,
                                     log, {.force = true}));
  // The ratio cycle with a timed chunk playing: its curve, gains and task frame every cycle.
  add(benchWrapper<CartesianCommand>(options, "cartesian_chunk", "cartesian_impedance", robot.home,
                                     log, {.chunked = true}));
  // The ratio cycle for drives with an onboard PD (the split into kp, kd, q_d, dq_d, tau_ff), and
  // in admittance for position drives (the virtual arm: its inertia factorised, one step).
  add(benchWrapper<CartesianCommand>(options, "cartesian_joint_pd", "cartesian_impedance",
                                     robot.home, log, {.output = OutputMode::kJointPd}));
  add(benchWrapper<CartesianCommand>(options, "cartesian_admittance", "cartesian_impedance",
                                     robot.home, log, {.output = OutputMode::kPosition}));
  return rows;
}

std::string benchRowsToJson(const BenchOptions& options, const std::vector<BenchRow>& rows) {
  nlohmann::json document;
  document["iterations"] = options.iterations;
  document["rows"] = nlohmann::json::array();
  for (const BenchRow& row : rows) {
    document["rows"].push_back({{"robot", row.robot},
                                {"dof", row.dof},
                                {"wrapper", row.wrapper},
                                {"plugin", row.plugin},
                                {"stage", row.stage},
                                {"mean_us", row.timing.mean_us},
                                {"sd_us", row.timing.sd_us},
                                {"p50_us", row.timing.p50_us},
                                {"p99_us", row.timing.p99_us},
                                {"p999_us", row.timing.p999_us},
                                {"max_us", row.timing.max_us},
                                {"p50_min_us", row.p50_min_us},
                                {"p50_max_us", row.p50_max_us},
                                {"processes", row.processes}});
  }
  document["reference"] = {
      {"published_step_us", kReferenceFigures.published_step_us},
      {"published_step_and_wrapper_us", kReferenceFigures.published_cycle_us},
      {"pinocchio_bundle_us",
       {kReferenceFigures.pinocchio_low_us, kReferenceFigures.pinocchio_high_us}},
      {"measured_on", kReferenceFigures.machine},
      {"date", kReferenceFigures.date},
      {"source", kReferenceFigures.source}};
  return document.dump(2);
}

std::vector<BenchRow> benchRowsFromJson(const std::string& text) {
  const nlohmann::json document = nlohmann::json::parse(text);
  std::vector<BenchRow> rows;
  for (const nlohmann::json& item : document.at("rows")) {
    BenchRow row;
    row.robot = item.at("robot").get<std::string>();
    row.dof = item.at("dof").get<int>();
    row.wrapper = item.at("wrapper").get<std::string>();
    row.plugin = item.at("plugin").get<std::string>();
    row.stage = item.at("stage").get<std::string>();
    row.timing = {item.at("mean_us").get<double>(), item.at("sd_us").get<double>(),
                  item.at("p50_us").get<double>(),  item.at("p99_us").get<double>(),
                  item.at("max_us").get<double>(),  item.value("p999_us", 0.0)};
    row.p50_min_us = item.value("p50_min_us", row.timing.p50_us);
    row.p50_max_us = item.value("p50_max_us", row.timing.p50_us);
    row.processes = item.value("processes", 1);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace comply::host
