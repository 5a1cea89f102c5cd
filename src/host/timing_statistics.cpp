#include "comply/host/timing_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace comply::host {
namespace {

/// Nearest-rank percentile of sorted samples: the smallest value with at least p % at or below.
/// p / 100 * n is rounded up, less a hair: 99.9 % of 1000 is 999, not the 999.0000000000001 that
/// binary 0.999 makes of it.
double percentile(const std::vector<double>& sorted, double p) {
  const double exact = p / 100.0 * static_cast<double>(sorted.size());
  const auto rank = static_cast<std::size_t>(std::ceil(exact - 1e-9 * exact));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

TimingSummary summarize(std::vector<double> samples_us) {
  if (samples_us.empty()) {
    throw std::invalid_argument("summarize: no samples");
  }
  std::sort(samples_us.begin(), samples_us.end());
  const auto n = static_cast<double>(samples_us.size());
  TimingSummary summary;
  summary.mean_us = std::accumulate(samples_us.begin(), samples_us.end(), 0.0) / n;
  double squares = 0.0;
  for (const double sample : samples_us) {
    squares += (sample - summary.mean_us) * (sample - summary.mean_us);
  }
  summary.sd_us = samples_us.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0;
  summary.p50_us = percentile(samples_us, 50.0);
  summary.p99_us = percentile(samples_us, 99.0);
  summary.p999_us = percentile(samples_us, 99.9);
  summary.max_us = samples_us.back();
  return summary;
}

}  // namespace comply::host
