// A wrapper's rows (see bench_rows.hpp), which robots a bench run names, and the merge of
// several processes' rows (see cycle_bench.hpp).

#include "bench_rows.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "comply/host/cycle_bench.hpp"
#include "comply/host/synthetic_chain.hpp"
#include "comply/model/robot_description.hpp"

namespace comply::host {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

BenchRow bench::benchRow(const RowNames& names, const char* stage, std::vector<double>& samples) {
  BenchRow result;
  result.wrapper = names.wrapper;
  result.plugin = names.plugin;
  result.stage = stage;
  result.timing = host::summarize(samples);
  result.p50_min_us = result.p50_max_us = result.timing.p50_us;
  return result;
}

std::vector<std::string> benchRobots(const std::string& robot_option) {
  if (robot_option == "all") {
    std::vector<std::string> robots = model::availableRobots();
    robots.push_back(syntheticChainName(12));
    return robots;
  }
  std::vector<std::string> robots;
  std::stringstream list(robot_option);
  for (std::string robot; std::getline(list, robot, ',');) {
    if (!robot.empty()) {
      robots.push_back(robot);
    }
  }
  if (robots.empty()) {
    throw std::runtime_error("--robot names no robot");
  }
  return robots;
}

std::vector<BenchRow> mergeBenchRuns(const std::vector<std::vector<BenchRow>>& runs) {
  if (runs.empty()) {
    throw std::invalid_argument("mergeBenchRuns: no runs");
  }
  std::vector<BenchRow> merged = runs.front();
  for (std::size_t r = 0; r < merged.size(); ++r) {
    std::vector<double> mean, sd, p50, p99, max, p999;
    for (const std::vector<BenchRow>& run : runs) {
      const BenchRow& row = run.at(r);
      if (row.wrapper != merged[r].wrapper || row.stage != merged[r].stage) {
        throw std::runtime_error("bench: processes reported different rows");
      }
      mean.push_back(row.timing.mean_us);
      sd.push_back(row.timing.sd_us);
      p50.push_back(row.timing.p50_us);
      p99.push_back(row.timing.p99_us);
      max.push_back(row.timing.max_us);
      p999.push_back(row.timing.p999_us);
    }
    merged[r].timing = {median(mean), median(sd),  median(p50),
                        median(p99),  median(max), median(p999)};
    merged[r].p50_min_us = *std::min_element(p50.begin(), p50.end());
    merged[r].p50_max_us = *std::max_element(p50.begin(), p50.end());
    merged[r].processes = static_cast<int>(runs.size());
  }
  return merged;
}

}  // namespace comply::host
