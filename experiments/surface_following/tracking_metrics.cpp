#include "surface_following/tracking_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <tuple>
#include <utility>
#include <vector>

#include "surface_following/fixture.hpp"

namespace comply::experiments::surface_following {
namespace {

constexpr double kContactForceN = 0.5;

/// One control cycle, seen from the probe ball.
struct Sample {
  double t = 0.0;
  Eigen::Vector3d tip, nominal, error;
  double lateral_m = 0.0;
  double tangential_m = 0.0;
  double contact_n = 0.0;
  double normal_n = 0.0;  // along the face's outward normal: the face pushing the probe out
  bool traversing = false;
};

Sample sampleAt(const host::SimLog& log, std::size_t row, const Eigen::Vector3d& averaged_force,
                const SurfaceStream& stream, const task::Path& tip_path) {
  Sample sample;
  sample.t = log.time_s[row];
  sample.tip =
      log.tcp_position[row] + log.tcp_orientation[row] * Eigen::Vector3d(0, 0, kProbeLength);
  sample.contact_n = averaged_force.norm();
  sample.traversing = sample.t >= stream.traverseStart() && sample.t <= stream.traverseEnd();
  const double s =
      std::clamp((sample.t - stream.traverseStart()) * stream.speed(), 0.0, tip_path.length());
  sample.nominal = tip_path.position(s);
  sample.error = sample.tip - sample.nominal;
  sample.lateral_m = sample.error.dot(outwardNormal(sample.nominal.x()));
  // The face under the probe: near the nominal point, and the displaced fixture turns by 2 deg
  // only, so its normal there differs by cos(2 deg) at most.
  sample.normal_n = averaged_force.dot(outwardNormal(sample.tip.x()));
  sample.tangential_m = sample.error.dot(tip_path.tangent(s));
  return sample;
}

void writeTraceLine(const Sample& sample, std::ostream& trace) {
  trace << sample.t << ',' << sample.tip.x() << ',' << sample.tip.y() << ',' << sample.tip.z()
        << ',' << sample.nominal.x() << ',' << sample.nominal.y() << ',' << 1e3 * sample.lateral_m
        << ',' << 1e3 * sample.tangential_m << ',' << sample.contact_n << ',' << sample.normal_n
        << '\n';
}

/// Distance from `tip` to the closest point of `path`, searched every 0.5 mm of arc length.
double distanceToPath(const Eigen::Vector3d& tip, const task::Path& path) {
  double closest = 1e9;
  for (double along = 0.0; along <= path.length(); along += 5e-4) {
    closest = std::min(closest, (tip - path.position(along)).norm());
  }
  return closest;
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) {
    sum += value * value;
  }
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

/// Mean and population standard deviation.
std::pair<double, double> meanAndSd(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double value : values) {
    mean += value / static_cast<double>(values.size());
  }
  double variance = 0.0;
  for (const double value : values) {
    variance += (value - mean) * (value - mean) / static_cast<double>(values.size());
  }
  return {mean, std::sqrt(variance)};
}

}  // namespace

SurfaceFollowingRow measureTracking(const std::string& condition, const host::SimLog& log,
                                    const SurfaceStream& stream, const task::Path& tip_path,
                                    const std::filesystem::path& trace_file) {
  SurfaceFollowingRow metrics;
  metrics.condition = condition;
  std::vector<double> lateral, tangential, total, force, normal_error;
  std::size_t in_contact = 0;
  // A force sensor's view: a 20 ms moving average (see host::averagedContactForce()).
  const std::vector<Eigen::Vector3d> averaged_force = host::averagedContactForce(log, 20);
  std::ofstream trace(trace_file);
  trace << "time_s,tip_x,tip_y,tip_z,nominal_x,nominal_y,lateral_mm,tangential_mm,force_n,"
           "normal_n\n";
  for (std::size_t row = 0; row < log.size(); ++row) {
    const Sample sample = sampleAt(log, row, averaged_force[row], stream, tip_path);
    writeTraceLine(sample, trace);
    if (!sample.traversing) {
      continue;
    }
    lateral.push_back(sample.lateral_m);
    tangential.push_back(sample.tangential_m);
    total.push_back(sample.error.norm());
    force.push_back(sample.contact_n);
    normal_error.push_back(sample.normal_n - kNormalForceN);
    in_contact += sample.contact_n > kContactForceN ? 1 : 0;
    metrics.max_distance_mm =
        std::max(metrics.max_distance_mm, 1e3 * distanceToPath(sample.tip, tip_path));
    metrics.lateral_max_mm = std::max(metrics.lateral_max_mm, 1e3 * std::abs(sample.lateral_m));
  }
  metrics.lateral_rms_mm = 1e3 * rms(lateral);
  metrics.tangential_rms_mm = 1e3 * rms(tangential);
  metrics.total_rmse_mm = 1e3 * rms(total);
  std::tie(metrics.force_mean_n, metrics.force_sd_n) = meanAndSd(force);
  metrics.normal_force_rmse_n = rms(normal_error);
  metrics.normal_force_rms_percent = 100.0 * metrics.normal_force_rmse_n / kNormalForceN;
  metrics.contact_fraction =
      force.empty() ? 0.0 : static_cast<double>(in_contact) / static_cast<double>(force.size());
  return metrics;
}

}  // namespace comply::experiments::surface_following
