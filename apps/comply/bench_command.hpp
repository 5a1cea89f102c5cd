#pragma once
// `comply bench`: the timing protocol of the evaluation. For the joint and the Cartesian wrapper
// on one robot: the plugin step alone, and the full cycle (model update + step + compensation +
// shaping), each timed per call over N iterations on a moving joint trajectory.

#include <iosfwd>
#include <string>
#include <vector>

#include "timing_statistics.hpp"

namespace comply::app {

struct BenchOptions {
  std::string robot = "fr3";
  int iterations = 10000;
  int warmup = 1000;
  int cpu = -1;  ///< pin the process to this CPU; -1 = leave to the scheduler
  bool json = false;
};

struct BenchRow {
  std::string wrapper;  ///< joint | cartesian (ratio damping) | cartesian_abs (absolute damping)
  std::string plugin;
  std::string stage;  ///< plugin_step | full_cycle
  TimingSummary timing;
};

/// Runs the benchmark; progress goes to `log` (stderr), never into the results.
std::vector<BenchRow> runBench(const BenchOptions& options, std::ostream& log);

/// Prints the table (or one JSON object with `rows`) and the published reference figures.
void printBench(const BenchOptions& options, int dof, const std::vector<BenchRow>& rows,
                std::ostream& out);

int benchCommand(const BenchOptions& options);

}  // namespace comply::app
