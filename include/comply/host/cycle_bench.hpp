#pragma once
// The cycle's timing protocol of the evaluation (`comply bench`): for the joint and the Cartesian
// wrapper on one robot, the plugin step alone and the full cycle (model update + step +
// compensation + shaping), each timed per call over N iterations on a moving joint trajectory;
// optionally paced at a robot's rate, and with the recording's push.
//
// Stable figures: the same binary measured 1.44 or 2.58 us for one cycle depending only on the
// size of the process environment, i.e. on where the stack starts relative to cache lines and
// pages. So `comply bench` measures each robot in several processes, each started with a
// different environment size, and reports the median over them (mergeBenchRuns) with the spread
// of their medians: a figure that moves with the layout shows it instead of hiding it.

#include <iosfwd>
#include <string>
#include <vector>

#include "comply/host/timing_statistics.hpp"

namespace comply::host {

/// Figures of the published implementation and a Pinocchio-based equivalent on the FR3, printed
/// beside ours so the numbers can be read in context. They were measured once on the development
/// machine, not on the machine that runs the bench: the output says where, when, and which page
/// holds them (docs/timing.md, "Against the paper's figures").
struct ReferenceFigures {
  double published_step_us;
  double published_cycle_us;  ///< step and wrapper
  double pinocchio_low_us;
  double pinocchio_high_us;
  const char* machine;
  const char* date;
  const char* source;
};
inline constexpr ReferenceFigures kReferenceFigures{
    7.2,
    8.3,
    1.8,
    2.5,
    "the development machine, a 2 vCPU VM with an AMD EPYC (AVX-512) and GCC 12",
    "2026-11-22",
    "docs/timing.md"};

struct BenchOptions {
  /// A robot name or folder, a comma-separated list of them, or "all": the four robots shipped
  /// and the synthetic 12-DOF chain. "chain<N>" names a synthetic N-joint chain.
  std::string robot = "fr3";
  int iterations = 10000;
  int warmup = 1000;
  int cpu = -1;       ///< pin the process to this CPU; -1 = leave to the scheduler
  int processes = 5;  ///< measuring processes per robot, each with another stack offset
  /// > 0: also the full cycle paced at this rate [Hz] on the wall clock, the control thread
  /// sleeping between cycles as a robot runs it (row stage "paced_cycle", at most 3 s of it),
  /// and the same with the thread spinning instead of sleeping ("paced_spin").
  double paced_hz = 0.0;
  bool json = false;
  bool worker = false;  ///< internal: measure one robot in this process, JSON rows on stdout
};

struct BenchRow {
  std::string robot;
  int dof = 0;
  std::string wrapper;  ///< joint | cartesian (ratio damping) | cartesian_abs (absolute damping)
  std::string plugin;
  std::string stage;        ///< plugin_step | full_cycle | paced_cycle | paced_spin
  TimingSummary timing;     ///< per field, the median over the processes
  double p50_min_us = 0.0;  ///< smallest and largest p50 of one process: the spread
  double p50_max_us = 0.0;
  int processes = 1;
};

/// Measures one robot (options.robot, a name or folder) in this process; progress goes to `log`
/// (stderr), never into the results.
std::vector<BenchRow> runBench(const BenchOptions& options, std::ostream& log);

/// The robots `options.robot` names, expanded ("all", lists).
std::vector<std::string> benchRobots(const std::string& robot_option);

/// The robots `options.robot` names, expanded ("all", lists).
std::vector<std::string> benchRobots(const std::string& robot_option);

/// The median of each statistic over per-process rows (same order in every process).
std::vector<BenchRow> mergeBenchRuns(const std::vector<std::vector<BenchRow>>& runs);

/// Rows as JSON (the worker's output and --json) and back.
std::string benchRowsToJson(const BenchOptions& options, const std::vector<BenchRow>& rows);
std::vector<BenchRow> benchRowsFromJson(const std::string& text);

}  // namespace comply::host
