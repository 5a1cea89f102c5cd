#include <cmath>
#include <fstream>
#include <iomanip>
#include <optional>
#include <ostream>

#include "comply/host/sim_session.hpp"

namespace comply::host {
namespace {

constexpr double kSettlePositionM = 0.001;
constexpr double kSettleOrientationRad = 0.5 * M_PI / 180.0;
constexpr double kSettleJointRad = 0.001;
constexpr std::size_t kMaxMessages = 8;

}  // namespace

void addMessage(SimSummary& summary, const std::string& message, std::ostream* progress) {
  if (summary.messages.size() < kMaxMessages) {
    summary.messages.push_back(message);
    if (progress != nullptr) {
      *progress << "\ncomply sim: " << message << "\n";
    }
  }
}

void summarizeLog(const SimLog& log, double end_of_motion_s, SimSummary& summary) {
  if (log.time_s.empty()) {
    return;
  }
  const std::size_t last = log.size() - 1;
  if (log.cartesian) {
    summary.final_position_error_mm = 1e3 * log.positionError(last);
    summary.final_orientation_error_deg = log.orientationError(last) * 180.0 / M_PI;
  } else {
    summary.final_joint_error_rad = log.jointError(last);
  }
  // Settling: the last row outside the band, counted from the end of the commanded motion.
  std::optional<std::size_t> last_outside;
  for (std::size_t row = 0; row < log.size(); ++row) {
    const bool outside = log.cartesian ? (log.positionError(row) > kSettlePositionM ||
                                          log.orientationError(row) > kSettleOrientationRad)
                                       : log.jointError(row) > kSettleJointRad;
    if (outside) {
      last_outside = row;
    }
  }
  if (!last_outside) {
    summary.settle_time_s = 0.0;
  } else if (*last_outside < last) {
    summary.settle_time_s = std::max(0.0, log.time_s[*last_outside + 1] - end_of_motion_s);
  }
}

double SimLog::positionError(std::size_t row) const {
  return (reference_position.at(row) - tcp_position.at(row)).norm();
}

double SimLog::orientationError(std::size_t row) const {
  return reference_orientation.at(row).angularDistance(tcp_orientation.at(row));
}

double SimLog::jointError(std::size_t row) const {
  return (joint_reference.at(row) - position.at(row)).cwiseAbs().maxCoeff();
}

std::vector<Eigen::Vector3d> averagedContactForce(const SimLog& log, std::size_t window) {
  std::vector<Eigen::Vector3d> averaged(log.size(), Eigen::Vector3d::Zero());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < log.size(); ++i) {
    sum += log.contact_wrench[i].head<3>();
    if (i >= window) {
      sum -= log.contact_wrench[i - window].head<3>();
    }
    averaged[i] = sum / static_cast<double>(std::min(i + 1, window));
  }
  return averaged;
}

void writeLogHeader(const SimLog& log, std::ostream& out) {
  out << "time_s";
  for (const char* prefix : {"q", "dq", "tau"}) {
    for (int j = 0; j < log.dof; ++j) {
      out << ',' << prefix << j;
    }
  }
  out << ",tcp_x,tcp_y,tcp_z,tcp_qx,tcp_qy,tcp_qz,tcp_qw";
  if (log.cartesian) {
    out << ",ref_x,ref_y,ref_z,ref_qx,ref_qy,ref_qz,ref_qw,position_error_mm,"
           "orientation_error_deg";
  } else {
    for (int j = 0; j < log.dof; ++j) {
      out << ",qref" << j;
    }
    out << ",joint_error_rad";
  }
  out << ",contact_fx,contact_fy,contact_fz,contact_tx,contact_ty,contact_tz";
  if (log.estimateLogged()) {
    out << ",estimated_fx,estimated_fy,estimated_fz,estimated_tx,estimated_ty,estimated_tz";
  }
  if (log.commandLogged()) {
    for (int j = 0; j < log.dof; ++j) {
      out << ",qcmd" << j;
    }
  }
  if (log.sensorLogged()) {
    out << ",sensor_fx,sensor_fy,sensor_fz,sensor_tx,sensor_ty,sensor_tz";
  }
  // Only a run with the tank on gets its columns: without it log.csv is what it always was.
  if (log.passivityEnabled()) {
    out << ",tank_energy_j,nullspace_tank_energy_j,energy_injected_j,energy_dissipated_j,"
           "energy_refused_j,gain_fraction";
  }
  out << '\n';
}

void writeLogRow(const SimLog& log, std::size_t row, std::ostream& out) {
  out << std::setprecision(9);
  const auto quaternion = [&](const Eigen::Quaterniond& q) {
    out << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << q.w();
  };
  out << log.time_s[row];
  for (const auto* column : {&log.position, &log.velocity, &log.torque}) {
    for (int j = 0; j < log.dof; ++j) {
      out << ',' << (*column)[row][j];
    }
  }
  const Eigen::Vector3d& p = log.tcp_position[row];
  out << ',' << p.x() << ',' << p.y() << ',' << p.z();
  quaternion(log.tcp_orientation[row]);
  if (log.cartesian) {
    const Eigen::Vector3d& r = log.reference_position[row];
    out << ',' << r.x() << ',' << r.y() << ',' << r.z();
    quaternion(log.reference_orientation[row]);
    out << ',' << 1e3 * log.positionError(row) << ',' << log.orientationError(row) * 180.0 / M_PI;
  } else {
    for (int j = 0; j < log.dof; ++j) {
      out << ',' << log.joint_reference[row][j];
    }
    out << ',' << log.jointError(row);
  }
  for (int k = 0; k < 6; ++k) {
    out << ',' << log.contact_wrench[row][k];
  }
  if (log.estimateLogged()) {
    for (int k = 0; k < 6; ++k) {
      out << ',' << log.estimated_wrench[row][k];
    }
  }
  if (log.commandLogged()) {
    for (int j = 0; j < log.dof; ++j) {
      out << ',' << log.position_command[row][j];
    }
  }
  if (log.sensorLogged()) {
    for (int k = 0; k < 6; ++k) {
      out << ',' << log.sensor_wrench[row][k];
    }
  }
  if (log.passivityEnabled()) {
    const pipeline::PassivitySnapshot& tank = log.passivity[row];
    out << ',' << tank.tank_energy_j << ',' << tank.nullspace_tank_energy_j << ','
        << tank.injected_j << ',' << tank.dissipated_j << ',' << tank.refused_j << ','
        << tank.gain_fraction;
  }
  out << '\n';
}

int simExitCode(const SimSummary& summary) {
  const bool failed = summary.faults > 0 || summary.last_command_rejected ||
                      summary.longest_saturation_s > kMaxSaturationS;
  return failed ? 1 : 0;
}

void printSummary(const SimSummary& summary, std::ostream& out) {
  out << std::fixed;
  out << "robot " << summary.robot << " (" << summary.dof << " DOF), plugin " << summary.plugin;
  if (summary.output_mode != OutputMode::kTorque) {
    out << ", " << toString(summary.output_mode) << " drives"
        << (isAdmittance(summary.output_mode) ? " (admittance: torques are the virtual arm's)"
                                              : "");
  }
  out << ": " << std::setprecision(2) << summary.simulated_s << " s simulated in " << summary.wall_s
      << " s (" << std::setprecision(1)
      << (summary.wall_s > 0 ? summary.simulated_s / summary.wall_s : 0.0) << "x real time)\n";
  if (summary.cartesian) {
    out << "  final pose error      " << std::setprecision(3) << summary.final_position_error_mm
        << " mm, " << summary.final_orientation_error_deg << " deg\n";
  } else {
    out << "  final joint error     " << std::setprecision(5) << summary.final_joint_error_rad
        << " rad\n";
  }
  out << "  settle time           ";
  if (std::isnan(summary.settle_time_s)) {
    out << "not settled\n";
  } else {
    out << std::setprecision(3) << summary.settle_time_s
        << " s after the last waypoint (band 1 mm, 0.5 deg)\n";
  }
  out << "  max torque            " << std::setprecision(2) << summary.max_torque_nm
      << " N m (joint " << summary.max_torque_joint << ")\n"
      << "  max torque rate       " << std::setprecision(1) << summary.max_torque_rate_nm_per_s
      << " N m/s\n"
      << "  rate-limit hits       " << summary.rate_limit_hits << " joint-cycles\n"
      << "  effort-limit hits     " << summary.effort_limit_hits << " joint-cycles\n"
      << "  governor hits         " << summary.governor_hits << " cycles\n"
      << "  wall hits             " << summary.wall_reference_hits << " cycles reference, "
      << summary.wall_brake_hits << " cycles braked\n"
      << "  contact-speed hits    " << summary.contact_speed_hits << " cycles\n"
      << "  commands              " << summary.commands_sent << " sent, " << summary.rejections
      << " rejected\n"
      << "  faults                " << summary.faults << "\n"
      << "  overruns              " << summary.overruns
      << " cycles (controller time above the period)\n"
      << "  cycle cost            p50 " << std::setprecision(2) << summary.cycle_cost.p50_us
      << " us, p99 " << summary.cycle_cost.p99_us << " us, mean " << summary.cycle_cost.mean_us
      << " us (controller only, plant excluded; unpinned)\n";
  // The verdicts last, where they are read: each one alone fails the run (exit 1).
  if (!summary.fault_reason.empty()) {
    out << "  FAULT: " << summary.fault_reason << "\n";
  }
  if (summary.last_command_rejected) {
    out << "  TARGET NOT REACHED: the task's last command was refused (" << summary.last_rejection
        << "); the errors above are against the last accepted reference\n";
  }
  if (summary.longest_saturation_s > kMaxSaturationS) {
    out << "  SATURATED: joint " << summary.saturated_joint << " at its effort limit for "
        << std::setprecision(2) << summary.longest_saturation_s << " s without a break (more than "
        << kMaxSaturationS << " s: the law lost control of it)\n";
  }
  for (const std::string& message : summary.messages) {
    out << "  note: " << message << "\n";
  }
  if (summary.recording) {
    const RecordingSummary& r = *summary.recording;
    out << "recording: " << r.written << " messages, " << std::setprecision(1)
        << static_cast<double>(r.bytes) / 1e6 << " MB, dropped " << r.dropped
        << "; writer thread CPU " << std::setprecision(2) << r.writer_cpu_s << " s\n";
    if (!r.error.empty()) {
      out << "recording stopped early: " << r.error << "\n";
    }
  }
  for (const std::filesystem::path& file : summary.files) {
    out << "  wrote " << file.string() << "\n";
  }
}

}  // namespace comply::host
