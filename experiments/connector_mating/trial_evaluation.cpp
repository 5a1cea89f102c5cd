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

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

/// What decides a trial besides depth and force: where the peg points, where its tip is, how far
/// the reference is ahead of the TCP and beside it, and where the stiff task axis points.
struct Geometry {
  Eigen::Vector3d tip;
  double peg_to_socket_deg;
  double tip_off_axis_mm;
  double lead_mm;
  double lateral_lag_mm;
  double orientation_lag_deg;
  double task_axis_to_socket_deg;
};

Geometry geometryAt(const host::SimLog& log, std::size_t i, const MatingStream& stream) {
  Geometry g{};
  const Eigen::Vector3d peg = log.tcp_orientation[i] * Eigen::Vector3d::UnitZ();
  g.tip = log.tcp_position[i] + kPegTip * peg;
  g.peg_to_socket_deg = angleDeg(peg, stream.axis());
  const Eigen::Vector3d from_entrance = g.tip - socketEntrance();
  g.tip_off_axis_mm =
      1e3 * (from_entrance - from_entrance.dot(stream.axis()) * stream.axis()).norm();
  const Eigen::Vector3d task_axis = stream.taskAxis(log.time_s[i], log.tcp_orientation[i]);
  const Eigen::Vector3d lag = log.reference_position[i] - log.tcp_position[i];
  g.lead_mm = 1e3 * lag.dot(task_axis);
  g.lateral_lag_mm = 1e3 * (lag - lag.dot(task_axis) * task_axis).norm();
  g.orientation_lag_deg = log.orientationError(i) * 180.0 / M_PI;
  g.task_axis_to_socket_deg = angleDeg(task_axis, stream.axis());
  return g;
}

}  // namespace

ConnectorMatingRow evaluateTrial(const Trial& trial, const host::SimLog& log,
                                 const MatingStream& stream, double force_limit,
                                 const std::filesystem::path& trace_file) {
  ConnectorMatingRow row;
  row.condition = trial.condition;
  row.offset_deg = trial.offset_rad * 180.0 / M_PI;
  row.seat_time_s = std::numeric_limits<double>::quiet_NaN();
  row.depth_mm = -std::numeric_limits<double>::infinity();  // negative: never reached the entrance
  const std::vector<Eigen::Vector3d> force = host::averagedContactForce(log, 20);
  const Eigen::Vector3d entrance = socketEntrance();
  std::ofstream trace(trace_file);
  trace << "time_s,depth_mm,axial_force_n,lateral_force_n,peg_to_socket_deg,tip_off_axis_mm,"
           "lead_mm,lateral_lag_mm,orientation_lag_deg,task_axis_to_socket_deg\n";
  bool failed = false;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const Geometry g = geometryAt(log, i, stream);
    const double depth = (g.tip - entrance).dot(stream.axis());
    // The environment pushes the peg back out: axial force is the component against the axis.
    const double axial = -force[i].dot(stream.axis());
    const double lateral = (force[i] + axial * stream.axis()).norm();
    trace << log.time_s[i] << ',' << 1e3 * depth << ',' << axial << ',' << lateral << ','
          << g.peg_to_socket_deg << ',' << g.tip_off_axis_mm << ',' << g.lead_mm << ','
          << g.lateral_lag_mm << ',' << g.orientation_lag_deg << ',' << g.task_axis_to_socket_deg
          << '\n';
    row.depth_mm = std::max(row.depth_mm, 1e3 * depth);
    if (!row.seated && !failed) {
      // Until the trial is decided (or the run ends): the state it was decided in.
      row.peak_axial_force_n = std::max(row.peak_axial_force_n, axial);
      row.peg_to_socket_deg = g.peg_to_socket_deg;
      row.task_axis_to_socket_deg = g.task_axis_to_socket_deg;
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
