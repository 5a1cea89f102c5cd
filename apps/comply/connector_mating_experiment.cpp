#include "connector_mating_experiment.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "controller_setup.hpp"
#include "sim_session.hpp"

namespace comply::app {
namespace {

// Peg and socket [m]. The socket's entrance centre is fixed; its axis is tilted about base x.
constexpr double kPegRadius = 0.006;
constexpr double kPegTip = 0.13;         // peg tip (capsule end) along TCP z, clear of the wrist
constexpr double kHoleRadius = 0.00625;  // 0.25 mm radial clearance
constexpr double kHoleDepth = 0.020;
constexpr double kChamfer = 0.006;
constexpr double kSeatTolerance = 0.001;
const Eigen::Vector3d kEntrance(0.45, 0.0, 0.20);
constexpr double kApproachS = 3.0;  // stiff, ends at rest above the entrance
constexpr double kInsertS = 4.0;
constexpr double kHoldS = 1.5;
constexpr double kStartAbove = 0.02;  // tip above the entrance along the axis
constexpr double kPastSeat = 0.01;    // the reference ends this far beyond the seat
constexpr double kLateralNPerM = 50.0;
constexpr double kAxialNPerM = 1000.0;

std::string pegFragment() {
  std::ostringstream xml;
  xml << "<mujocoinclude>\n  <geom name=\"peg\" type=\"capsule\" fromto=\"0 0 0.005 0 0 "
      << kPegTip - kPegRadius << "\" size=\"" << kPegRadius
      << "\" rgba=\"0.8 0.55 0.15 1\" mass=\"0.05\" friction=\"0.3 0.005 0.0001\"/>\n"
      << "</mujocoinclude>\n";
  return xml.str();
}

/// A ring of 16 walls around a round hole with a 45 deg entry chamfer, and the seat at the
/// bottom; the whole socket tilted by `tilt` about x. Connectors have such a chamfer: it takes
/// up the few millimetres by which a compliant arm with joint friction misses the entrance.
std::string socketFragment(double tilt) {
  std::ostringstream xml;
  xml << std::setprecision(9) << "<mujocoinclude>\n  <body name=\"socket\" pos=\"" << kEntrance.x()
      << " " << kEntrance.y() << " " << kEntrance.z() << "\" quat=\"" << std::cos(0.5 * tilt) << " "
      << std::sin(0.5 * tilt) << " 0 0\">\n";
  const int sides = 16;
  const double wall = 0.01;
  const double half_width = (kHoleRadius + kChamfer + wall) * std::tan(M_PI / sides) + 5e-4;
  const auto box = [&](const Eigen::Vector3d& centre, const Eigen::Quaterniond& rotation,
                       const Eigen::Vector3d& half_size) {
    xml << "    <geom type=\"box\" size=\"" << half_size.transpose() << "\" pos=\""
        << centre.transpose() << "\" quat=\"" << rotation.w() << " " << rotation.x() << " "
        << rotation.y() << " " << rotation.z()
        << "\" rgba=\"0.4 0.45 0.5 1\" friction=\"0.3 0.005 0.0001\" solref=\"0.005 1\"/>\n";
  };
  for (int i = 0; i < sides; ++i) {
    const Eigen::Quaterniond around(
        Eigen::AngleAxisd(2.0 * M_PI * i / sides, Eigen::Vector3d::UnitZ()));
    // Straight wall below the chamfer: inner face at the hole radius.
    const double wall_length = kHoleDepth - kChamfer;
    box(around * Eigen::Vector3d(kHoleRadius + 0.5 * wall, 0.0, -kChamfer - 0.5 * wall_length),
        around, Eigen::Vector3d(0.5 * wall, half_width, 0.5 * wall_length));
    // Chamfer: inner face through (r, -c) and (r + c, 0), thickness outwards and down.
    const Eigen::Quaterniond tilted =
        around * Eigen::AngleAxisd(M_PI / 4.0, Eigen::Vector3d::UnitY());
    const Eigen::Vector3d face_middle(kHoleRadius + 0.5 * kChamfer, 0.0, -0.5 * kChamfer);
    const Eigen::Vector3d outward_down = Eigen::Vector3d(1.0, 0.0, -1.0).normalized();
    box(around * (face_middle + 0.5 * wall * outward_down), tilted,
        Eigen::Vector3d(0.5 * wall, half_width, kChamfer / std::sqrt(2.0)));
  }
  xml << "    <geom type=\"box\" size=\"0.02 0.02 0.005\" pos=\"0 0 " << -kHoleDepth - 0.005
      << "\" rgba=\"0.3 0.35 0.4 1\" solref=\"0.005 1\"/>\n  </body>\n</mujocoinclude>\n";
  return xml.str();
}

/// Where the insertion gains (stiff along z, soft across) are expressed.
enum class ComplianceFrame {
  kCommandedTcp,  ///< the commanded TCP orientation: z along the peg as commanded
  kMeasuredTcp,   ///< the measured TCP, every cycle: z along the peg as it is
  kSocket,        ///< the socket's frame: z along the insertion axis
};

struct Trial {
  std::string condition;
  ComplianceFrame frame = ComplianceFrame::kCommandedTcp;
  double offset_rad = 0.0;
};

ComplianceFrame complianceFrameOf(const std::string& condition) {
  if (condition == "tcp_fixed") {
    return ComplianceFrame::kCommandedTcp;
  }
  if (condition == "tcp_measured") {
    return ComplianceFrame::kMeasuredTcp;
  }
  if (condition == "task_aligned") {
    return ComplianceFrame::kSocket;
  }
  throw std::invalid_argument("unknown connector-mating condition '" + condition +
                              "' (tcp_fixed, tcp_measured or task_aligned)");
}

/// Unit axis into the socket, base frame.
Eigen::Vector3d socketAxis(double tilt) {
  return Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0.0, 0.0, -1.0);
}

class MatingCommand {
 public:
  MatingCommand(const Trial& trial, const Eigen::Vector3d& home_tcp,
                const Eigen::Quaterniond& peg_down, double rotational_nm_per_rad, int dof)
      : trial_(trial),
        home_tcp_(home_tcp),
        peg_down_(peg_down),
        rotational_nm_per_rad_(rotational_nm_per_rad),
        dof_(dof) {
    axis_ = socketAxis(trial.offset_rad);
    // TCP = tip - R (0, 0, kPegTip); the commanded orientation keeps the peg vertical.
    tip_to_tcp_ = -(peg_down_ * Eigen::Vector3d(0.0, 0.0, kPegTip));
    start_tcp_ = kEntrance - kStartAbove * axis_ + tip_to_tcp_;
    end_tcp_ = kEntrance + (kHoleDepth + kPastSeat) * axis_ + tip_to_tcp_;
  }

  static double duration() { return kApproachS + kInsertS + kHoldS; }

  CartesianCommand operator()(double t) const {
    CartesianCommand command = CartesianCommand::zero(dof_);
    command.stamp_s = t;
    command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
                     CommandField::kDamping | CommandField::kTaskFrame;
    command.orientation = peg_down_;
    command.damping_mode = DampingMode::kRatio;
    command.damping_ratio.setOnes();
    command.stiffness_rotational = Eigen::Matrix3d::Identity() * rotational_nm_per_rad_;
    if (t < kApproachS) {
      const double s = std::min(1.0, t / (kApproachS - 1.0));
      command.position = home_tcp_ + s * (start_tcp_ - home_tcp_);
      if (s < 1.0) {
        command.twist.head<3>() = (start_tcp_ - home_tcp_) / (kApproachS - 1.0);
      }
      command.stiffness_translational = Eigen::Matrix3d::Identity() * 3000.0;
      command.stiffness_rotational = Eigen::Matrix3d::Identity() * 100.0;
      return command;
    }
    const double s = std::min(1.0, (t - kApproachS) / kInsertS);
    command.position = start_tcp_ + s * (end_tcp_ - start_tcp_);
    if (s < 1.0) {
      command.twist.head<3>() = (end_tcp_ - start_tcp_) / kInsertS;
    }
    command.stiffness_translational =
        Eigen::Vector3d(kLateralNPerM, kLateralNPerM, kAxialNPerM).asDiagonal();
    switch (trial_.frame) {
      case ComplianceFrame::kCommandedTcp:
        command.task_frame = peg_down_;
        break;
      case ComplianceFrame::kMeasuredTcp:
        command.task_frame = Eigen::Quaterniond::Identity();  // relative to the measured TCP
        break;
      case ComplianceFrame::kSocket:
        command.task_frame = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis_);
        break;
    }
    return command;
  }

  [[nodiscard]] const Eigen::Vector3d& axis() const { return axis_; }

 private:
  Trial trial_;
  Eigen::Vector3d home_tcp_;
  Eigen::Quaterniond peg_down_;
  double rotational_nm_per_rad_;
  int dof_;
  Eigen::Vector3d axis_;
  Eigen::Vector3d tip_to_tcp_;
  Eigen::Vector3d start_tcp_;
  Eigen::Vector3d end_tcp_;
};

ConnectorMatingRow evaluate(const Trial& trial, const SimLog& log, const MatingCommand& command,
                            double force_limit, const std::filesystem::path& trace_file) {
  ConnectorMatingRow row;
  row.condition = trial.condition;
  row.offset_deg = trial.offset_rad * 180.0 / M_PI;
  row.seat_time_s = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector3d> force = averagedContactForce(log, 20);
  std::ofstream trace(trace_file);
  trace << "time_s,depth_mm,axial_force_n,lateral_force_n\n";
  bool failed = false;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const Eigen::Vector3d tip =
        log.tcp_position[i] + log.tcp_orientation[i] * Eigen::Vector3d(0.0, 0.0, kPegTip);
    const double depth = (tip - kEntrance).dot(command.axis());
    // The environment pushes the peg back out: axial force is the component against the axis.
    const double axial = -force[i].dot(command.axis());
    const double lateral = (force[i] + axial * command.axis()).norm();
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

}  // namespace

std::vector<ConnectorMatingRow> runConnectorMating(const ConnectorMatingOptions& options) {
  std::filesystem::create_directories(options.out_dir);
  const TcpPose home = homeTcpPose("fr3");
  const std::filesystem::path peg_file = options.out_dir / "peg.xml";
  std::ofstream(peg_file) << pegFragment();

  // Refuse an unknown condition before the first trial rather than after minutes of others.
  for (const std::string& condition : options.conditions) {
    complianceFrameOf(condition);
  }
  std::vector<ConnectorMatingRow> rows;
  for (const double offset_deg : options.offsets_deg) {
    for (const std::string& condition : options.conditions) {
      const Trial trial{condition, complianceFrameOf(condition), offset_deg * M_PI / 180.0};
      std::ostringstream name;
      name << trial.condition << "_" << offset_deg << "deg";
      const std::filesystem::path folder = options.out_dir / name.str();
      std::filesystem::create_directories(folder);
      std::ofstream(folder / "socket.xml") << socketFragment(trial.offset_rad);

      SimRunOptions run;
      run.config = simControllerConfig(
          "fr3", "",
          (std::filesystem::path(COMPLY_SOURCE_DIR) / "config/sim/cartesian_impedance.yaml")
              .string());
      if (trial.frame == ComplianceFrame::kMeasuredTcp) {
        plugin::ParameterValue reference;
        reference.text = "tcp";
        reference.is_text = true;
        run.config.plugin_parameters["task_frame_reference"] = reference;
      }
      const MatingCommand command(trial, home.position, home.orientation,
                                  options.rotational_stiffness_nm_per_rad, run.config.dof);
      run.task = parseTaskFile(
          "task:\n  command_rate_hz: 100\n  scene: {substeps: 4}\n  camera: {lookat: [0.45, 0.0, "
          "0.22], distance_m: 0.5, azimuth_deg: 90, elevation_deg: -15}\n  waypoints: "
          "[{time_s: " +
              std::to_string(kApproachS + kInsertS) + "}]\n",
          "connector-mating task", options.out_dir, true, run.config.dof);
      run.task.scene.tool = peg_file;
      run.task.scene.objects.push_back(folder / "socket.xml");
      run.duration_s = MatingCommand::duration();
      run.out_dir = folder;
      run.snapshots = options.pictures;
      run.progress = options.progress;
      run.plant_friction_scale = options.plant_friction_scale;
      run.cartesian_source = std::make_shared<task::FunctionSource<CartesianCommand>>(
          [&command](double t, const MeasuredPose&) { return command(t); });
      const SimResult result = runSimulation(run);
      rows.push_back(
          evaluate(trial, result.log, command, options.axial_force_limit_n, folder / "trace.csv"));
    }
  }

  nlohmann::json results = nlohmann::json::array();
  for (const ConnectorMatingRow& row : rows) {
    results.push_back(
        {{"condition", row.condition},
         {"offset_deg", row.offset_deg},
         {"seated", row.seated},
         {"failure", row.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(row.failure)},
         {"depth_mm", row.depth_mm},
         {"peak_axial_force_n", row.peak_axial_force_n},
         {"seat_time_s", std::isfinite(row.seat_time_s) ? nlohmann::json(row.seat_time_s)
                                                        : nlohmann::json(nullptr)}});
  }
  std::ofstream(options.out_dir / "results.json") << results.dump(2) << "\n";
  std::ofstream table(options.out_dir / "table.md");
  printConnectorMatingTable(rows, table);
  return rows;
}

void printConnectorMatingTable(const std::vector<ConnectorMatingRow>& rows, std::ostream& out) {
  out << "| offset [deg] | condition | seated | depth [mm] | peak axial force [N] | seat time [s] "
         "| failure |\n|---|---|---|---|---|---|---|\n"
      << std::fixed;
  for (const ConnectorMatingRow& row : rows) {
    out << "| " << std::setprecision(0) << row.offset_deg << " | " << row.condition << " | "
        << (row.seated ? "yes" : "no") << " | " << std::setprecision(1) << row.depth_mm << " | "
        << row.peak_axial_force_n << " | ";
    if (row.seated) {
      out << std::setprecision(2) << row.seat_time_s;
    } else {
      out << "-";
    }
    out << " | " << (row.failure.empty() ? "-" : row.failure) << " |\n";
  }
}

int connectorMatingCommand(const ConnectorMatingOptions& options, std::ostream& out,
                           std::ostream& err) {
  ConnectorMatingOptions run = options;
  run.progress = &err;
  printConnectorMatingTable(runConnectorMating(run), out);
  out << "results in " << std::filesystem::absolute(options.out_dir).string() << "\n";
  return 0;
}

}  // namespace comply::app
