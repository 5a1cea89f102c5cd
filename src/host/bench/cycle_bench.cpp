// The cycle's timing protocol (see cycle_bench.hpp): each wrapper and variant set up
// (bench_variant.hpp), timed (bench_loops.hpp) and summarised into rows (bench_rows.hpp).

#include "comply/host/cycle_bench.hpp"

#include <sched.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <type_traits>

#include "bench_loops.hpp"
#include "bench_rows.hpp"
#include "bench_variant.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::host {
namespace {

using bench::Variant;

template <typename Command>
std::vector<BenchRow> benchWrapper(const BenchOptions& options, const std::string& wrapper_name,
                                   const std::string& plugin_name, const std::vector<double>& home,
                                   std::ostream& log, const Variant& variant = {}) {
  const pipeline::WrapperConfig config = bench::variantConfig(options.robot, plugin_name, variant);
  const auto resolved = pipeline::resolveController(config);
  pipeline::Wrapper<Command> wrapper(resolved);
  const int total = options.warmup + options.iterations;
  bench::ReplayHardware replay(home, total);
  wrapper.activate(replay.at(0));
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    bench::submitVariantCommands(wrapper, variant, wrapper_name, 1.5 * total * bench::kPeriodS);
  }
  std::vector<double> step_us;
  std::vector<double> cycle_us;
  step_us.reserve(static_cast<std::size_t>(options.iterations));
  cycle_us.reserve(static_cast<std::size_t>(options.iterations));

  // Full cycles first, through the control loop every host runs.
  bench::FullCycles<Command> full(wrapper, replay, total, options.warmup, cycle_us);
  if (variant.recorded) {
    full.record(wrapper_name);
  }
  full.run(wrapper_name);
  // Then the law alone on the same trajectory, with the model updated untimed before each step.
  bench::pluginSteps(wrapper.controller(), replay, total, options.warmup, wrapper_name, step_us);
  log << "  " << wrapper_name << " (" << plugin_name << "): " << options.iterations
      << " cycles done\n";

  const bench::RowNames names{wrapper_name, plugin_name};
  std::vector<BenchRow> rows{bench::benchRow(names, "plugin_step", step_us),
                             bench::benchRow(names, "full_cycle", cycle_us)};
  if (BenchRecording<Command>* recording = full.recording()) {
    rows.push_back(bench::benchRow(names, "record_push", recording->push_us));
    std::vector<double> full_us = recording->fullLanePushes(options.warmup, options.iterations);
    rows.push_back(bench::benchRow(names, "record_push_full", full_us));
    rows.push_back(bench::benchRow(names, "state_sample", recording->sample_us));
  }
  if (options.paced_hz > 0.0) {
    bench::appendPacedRows(wrapper, home, options, total, names, rows);
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
  // The ratio cycle with walls and a box configured (the reference kept inside, the barrier).
  add(benchWrapper<CartesianCommand>(options, "cartesian_walls", "cartesian_impedance", robot.home,
                                     log, {.walls = true}));
  // The observer's cycle with the contact reflex armed (contact_reflex.hpp).
  add(benchWrapper<CartesianCommand>(options, "cartesian_reflex", "cartesian_impedance", robot.home,
                                     log, {.reflex = true}));
  // The ratio cycle with the contact-speed stage: the arm's mass along the TCP's motion (the
  // inertia with the rotors' factorised, one solve) every cycle.
  add(benchWrapper<CartesianCommand>(options, "cartesian_contact", "cartesian_impedance",
                                     robot.home, log, {.contact_speed = true}));
  // The three safety stages together (walls, reflex, contact speed) on the observer's cycle: what
  // they cost over cartesian_observer is their budget's measure.
  add(benchWrapper<CartesianCommand>(options, "cartesian_safety", "cartesian_impedance", robot.home,
                                     log, {.walls = true, .reflex = true, .contact_speed = true}));
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

}  // namespace comply::host
