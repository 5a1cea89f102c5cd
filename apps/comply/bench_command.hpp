#pragma once
// `comply bench`: the cycle's timing protocol (comply/host/cycle_bench.hpp) in several processes
// per robot (bench_processes.cpp), printed as a table or JSON.

#include <iosfwd>
#include <vector>

#include "comply/host/cycle_bench.hpp"

namespace comply::app {

using host::BenchOptions;
using host::benchRobots;
using host::BenchRow;
using host::benchRowsFromJson;
using host::benchRowsToJson;
using host::mergeBenchRuns;
using host::runBench;

/// Runs options.processes worker processes of this executable per robot, each with its own
/// environment size, and merges their rows: median per statistic, spread of the p50s.
std::vector<BenchRow> runBenchProcesses(const BenchOptions& options, std::ostream& log);

/// Prints the table (or one JSON object with `rows`) and the reference figures of other
/// implementations, with the machine and date they were measured on (not this machine).
void printBench(const BenchOptions& options, const std::vector<BenchRow>& rows, std::ostream& out);

int benchCommand(const BenchOptions& options);

}  // namespace comply::app
