#pragma once
// A benchmarked wrapper's rows (cycle_bench.cpp): each timed stage's samples summarised under the
// wrapper's and plugin's names. Private to the host.

#include <string>
#include <vector>

#include "comply/host/cycle_bench.hpp"

namespace comply::host::bench {

/// The wrapper and the plugin a row is of.
struct RowNames {
  const std::string& wrapper;
  const std::string& plugin;
};

/// The row of `stage`: the summary of `samples`, its own p50 as the spread of one process.
BenchRow benchRow(const RowNames& names, const char* stage, std::vector<double>& samples);

}  // namespace comply::host::bench
