#pragma once
// Summary statistics of a series of timings, as the benchmark protocol reports them.

#include <vector>

namespace comply::host {

struct TimingSummary {
  double mean_us = 0.0;
  double sd_us = 0.0;  ///< sample standard deviation
  double p50_us = 0.0;
  double p99_us = 0.0;
  double max_us = 0.0;
  double p999_us = 0.0;  ///< the 99.9th percentile: a paced cycle's tail
};

/// Statistics of `samples_us` (at least one sample). Percentiles by nearest rank.
TimingSummary summarize(std::vector<double> samples_us);

}  // namespace comply::host
