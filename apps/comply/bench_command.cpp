#include "bench_command.hpp"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace comply::app {
void printBench(const BenchOptions& options, const std::vector<BenchRow>& rows, std::ostream& out) {
  if (options.json) {
    out << benchRowsToJson(options, rows) << "\n";
    return;
  }
  const int processes = rows.empty() ? 0 : rows.front().processes;
  out << options.iterations << " iterations per process, " << processes
      << " processes per robot with different stack offsets; microseconds per call, median over "
         "the processes;\nspread: smallest and largest p50 of one process, relative to the "
         "median\n\n";
  out << std::left << std::setw(9) << "robot" << std::right << std::setw(4) << "dof"
      << "  " << std::left << std::setw(22) << "wrapper" << std::setw(18) << "stage" << std::right
      << std::setw(9) << "mean" << std::setw(9) << "p50" << std::setw(9) << "p99" << std::setw(9)
      << "p99.9" << std::setw(9) << "max" << std::setw(17) << "p50 spread"
      << "\n";
  for (const BenchRow& row : rows) {
    const double median = row.timing.p50_us;
    out << std::left << std::setw(9) << row.robot << std::right << std::setw(4) << row.dof << "  "
        << std::left << std::setw(22) << row.wrapper << std::setw(18) << row.stage << std::right
        << std::fixed << std::setprecision(3) << std::setw(9) << row.timing.mean_us << std::setw(9)
        << row.timing.p50_us << std::setw(9) << row.timing.p99_us << std::setw(9)
        << row.timing.p999_us << std::setw(9) << row.timing.max_us << std::setprecision(1)
        << std::setw(8) << 100.0 * (row.p50_min_us - median) / median << "% " << std::showpos
        << std::setw(6) << 100.0 * (row.p50_max_us - median) / median << "%" << std::noshowpos
        << "\n";
  }
  out << std::setprecision(1) << "\nfor reference (fr3, measured on "
      << host::kReferenceFigures.machine << ", on " << host::kReferenceFigures.date << "; "
      << host::kReferenceFigures.source << "): published implementation "
      << host::kReferenceFigures.published_step_us << " us (step) / "
      << host::kReferenceFigures.published_cycle_us
      << " us (step + wrapper); an equivalent Pinocchio bundle "
      << host::kReferenceFigures.pinocchio_low_us << "-"
      << host::kReferenceFigures.pinocchio_high_us << " us\n";
}

int benchCommand(const BenchOptions& options) {
  if (options.worker) {
    std::ostringstream quiet;  // the parent reports progress, once per process
    const std::vector<BenchRow> rows = runBench(options, quiet);
    std::cout << benchRowsToJson(options, rows) << "\n";
    return 0;
  }
  printBench(options, runBenchProcesses(options, std::cerr), std::cout);
  return 0;
}

}  // namespace comply::app
