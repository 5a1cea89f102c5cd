#include "connector_mating/trial_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "connector_mating/peg_and_socket.hpp"

namespace comply::experiments::connector_mating {
namespace {

constexpr double kSeatTolerance = 0.001;

}  // namespace

ConnectorMatingRow evaluateTrial(const Trial& trial, const app::SimLog& log,
                                 const MatingStream& stream, double force_limit,
                                 const std::filesystem::path& trace_file) {
  ConnectorMatingRow row;
  row.condition = trial.condition;
  row.offset_deg = trial.offset_rad * 180.0 / M_PI;
  row.seat_time_s = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector3d> force = app::averagedContactForce(log, 20);
  const Eigen::Vector3d entrance = socketEntrance();
  std::ofstream trace(trace_file);
  trace << "time_s,depth_mm,axial_force_n,lateral_force_n\n";
  bool failed = false;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const Eigen::Vector3d tip =
        log.tcp_position[i] + log.tcp_orientation[i] * Eigen::Vector3d(0.0, 0.0, kPegTip);
    const double depth = (tip - entrance).dot(stream.axis());
    // The environment pushes the peg back out: axial force is the component against the axis.
    const double axial = -force[i].dot(stream.axis());
    const double lateral = (force[i] + axial * stream.axis()).norm();
    trace << log.time_s[i] << ',' << 1e3 * depth << ',' << axial << ',' << lateral << '\n';
    row.depth_mm = std::max(row.depth_mm, 1e3 * depth);
    if (!row.seated && !failed) {
      row.peak_axial_force_n = std::max(row.peak_axial_force_n, axial);
      if (axial > force_limit) {
        failed = true;
      } else if (depth >= kHoleDepth - kSeatTolerance) {
        row.seated = true;
        row.seat_time_s = log.time_s[i];
      }
    }
  }
  if (!row.seated) {
    row.failure = failed ? "force_limit" : "time_out";
  }
  return row;
}

}  // namespace comply::experiments::connector_mating
