#include "surface_following_experiment.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "comply/task/path_command.hpp"
#include "controller_setup.hpp"
#include "sim_command.hpp"
#include "sim_session.hpp"

namespace comply::app {
namespace {

// Fixture and probe geometry [m], base frame. The fixture's curved face runs along x; its
// material lies on the -y side, the probe presses from +y.
constexpr double kPathStartX = 0.35;
constexpr double kPathLengthX = 0.18;
constexpr double kBulge = 0.03;        // max lateral deviation of the face
constexpr double kTipZ = 0.25;         // height of the probe ball's centre
constexpr double kProbeLength = 0.10;  // ball centre below the TCP (probe_tool.xml)
constexpr double kTipRadius = 0.01;
constexpr double kPressDepth = 0.10;  // reference into the surface: 5 N at 50 N/m
constexpr double kApproachClearance = 0.03;
constexpr double kApproachS = 2.5;
constexpr double kContactS = 2.0;
constexpr double kHoldS = 1.0;
constexpr double kCompliantNPerM = 50.0;
constexpr double kStiffNPerM = 1000.0;
constexpr double kContactForceN = 0.5;
// The displaced run: the fixture moved 8 mm towards the probe and turned 2 deg about z.
constexpr double kDisplacementY = 0.008;
constexpr double kDisplacementYawRad = 2.0 * M_PI / 180.0;

double faceY(double x) {
  const double u = std::clamp((x - kPathStartX) / kPathLengthX, 0.0, 1.0);
  return kBulge * std::sin(M_PI * u) * std::sin(M_PI * u);
}
double faceSlope(double x) {
  const double u = (x - kPathStartX) / kPathLengthX;
  if (u <= 0.0 || u >= 1.0) {
    return 0.0;
  }
  return kBulge * M_PI / kPathLengthX * std::sin(2.0 * M_PI * u);
}
/// Unit normal of the face pointing out of the material, towards the probe (horizontal).
Eigen::Vector3d outwardNormal(double x) {
  return Eigen::Vector3d(-faceSlope(x), 1.0, 0.0).normalized();
}

/// Where the probe ball's centre should be: the face, one ball radius out.
Eigen::Vector3d nominalTip(double x) {
  return Eigen::Vector3d(x, faceY(x), kTipZ) + kTipRadius * outwardNormal(x);
}

std::vector<Eigen::Vector3d> nominalTipPoints(double fraction) {
  std::vector<Eigen::Vector3d> points;
  const int count = 2000;
  for (int i = 0; i <= count; ++i) {
    points.push_back(nominalTip(kPathStartX + fraction * kPathLengthX * i / count));
  }
  return points;
}

/// The fixture as boxes tangent to the face, displaced by (dy, yaw about the path's middle).
std::string fixtureFragment(double dy, double yaw) {
  const Eigen::Vector2d pivot(kPathStartX + 0.5 * kPathLengthX, 0.0);
  const Eigen::Rotation2Dd turn(yaw);
  const auto place = [&](const Eigen::Vector2d& point) {
    return Eigen::Vector2d(turn * (point - pivot) + pivot + Eigen::Vector2d(0.0, dy));
  };
  std::ostringstream xml;
  xml << std::setprecision(9) << "<mujocoinclude>\n  <body name=\"fixture\" pos=\"0 0 " << kTipZ
      << "\">\n";
  const int segments = 90;
  const double begin = kPathStartX - 0.04;
  const double end = kPathStartX + kPathLengthX + 0.04;
  const double thickness = 0.04;
  for (int i = 0; i < segments; ++i) {
    const double xa = begin + (end - begin) * i / segments;
    const double xb = begin + (end - begin) * (i + 1) / segments;
    const Eigen::Vector2d a = place({xa, faceY(xa)});
    const Eigen::Vector2d b = place({xb, faceY(xb)});
    const Eigen::Vector2d along = (b - a).normalized();
    const Eigen::Vector2d inward(along.y(), -along.x());  // material side (-y for yaw 0)
    const Eigen::Vector2d centre = 0.5 * (a + b) + 0.5 * thickness * inward;
    const double angle = std::atan2(along.y(), along.x());
    xml << "    <geom type=\"box\" size=\"" << 0.5 * (b - a).norm() + 5e-4 << " " << 0.5 * thickness
        << " 0.025\" pos=\"" << centre.x() << " " << centre.y() << " 0\" quat=\""
        << std::cos(0.5 * angle) << " 0 0 " << std::sin(0.5 * angle)
        << "\" rgba=\"0.45 0.55 0.7 1\" friction=\"0.2 0.005 0.0001\" solref=\"0.005 1\"/>\n";
  }
  xml << "  </body>\n</mujocoinclude>\n";
  return xml.str();
}

struct Condition {
  std::string name;
  bool task_aligned = true;
  bool displaced = false;
};

/// Commands of one run: approach in free space, press onto the start, traverse, hold.
class SurfaceCommand {
 public:
  SurfaceCommand(const Condition& condition, const Eigen::Vector3d& home_tcp,
                 const Eigen::Quaterniond& orientation, double speed, double fraction, int dof)
      : condition_(condition),
        home_tcp_(home_tcp),
        dof_(dof),
        stream_(tcpPath(fraction), streamOptions(orientation, speed)) {
    start_tcp_ = stream_.commandAt(traverseStart(), dof).position;
    approach_tcp_ = stream_.path().position(0.0) + kApproachClearance * outwardNormal(kPathStartX);
  }

  static double traverseStart() { return kApproachS + kContactS; }
  [[nodiscard]] double traverseEnd() const {
    return traverseStart() + stream_.path().length() / speed();
  }
  [[nodiscard]] double duration() const { return traverseEnd() + kHoldS; }
  [[nodiscard]] double speed() const { return speed_; }

  CartesianCommand operator()(double t) {
    CartesianCommand command = stream_.commandAt(std::max(t, traverseStart()), dof_);
    command.stamp_s = t;
    if (t < kApproachS) {
      // Free space: stiff in every direction, gains in the base frame.
      const double s = t / kApproachS;
      command.position = home_tcp_ + s * (approach_tcp_ - home_tcp_);
      command.twist.head<3>() = (approach_tcp_ - home_tcp_) / kApproachS;
      command.task_frame = Eigen::Quaterniond::Identity();
      command.stiffness_translational = Eigen::Vector3d::Constant(kStiffNPerM).asDiagonal();
      return command;
    }
    if (t < traverseStart()) {
      const double s = (t - kApproachS) / kContactS;
      command.position = approach_tcp_ + s * (start_tcp_ - approach_tcp_);
      command.twist.head<3>() = (start_tcp_ - approach_tcp_) / kContactS;
    }
    if (!condition_.task_aligned) {
      command.task_frame = Eigen::Quaterniond::Identity();  // 50 N/m stays along base y
    }
    return command;
  }

  [[nodiscard]] const task::PathCommand& stream() const { return stream_; }

 private:
  static task::Path tcpPath(double fraction) {
    std::vector<Eigen::Vector3d> points = nominalTipPoints(fraction);
    for (Eigen::Vector3d& point : points) {
      point.z() += kProbeLength;
    }
    return task::Path(points);
  }
  task::PathCommandOptions streamOptions(const Eigen::Quaterniond& orientation, double speed) {
    speed_ = speed;
    task::PathCommandOptions options;
    options.speed_m_per_s = speed;
    options.start_time_s = traverseStart();
    options.frame = task::FrameSource::kDarboux;
    // The controller's idea of the fixture: always the nominal one.
    options.surface_normal = [](const Eigen::Vector3d& point) { return outwardNormal(point.x()); };
    options.stiffness_translational = Eigen::Vector3d(kStiffNPerM, kCompliantNPerM, kStiffNPerM);
    options.stiffness_rotational = Eigen::Vector3d::Constant(100.0);
    options.offset_in_task_frame = Eigen::Vector3d(0.0, -kPressDepth, 0.0);
    options.orientation = orientation;
    return options;
  }

  Condition condition_;
  Eigen::Vector3d home_tcp_;
  int dof_;
  double speed_ = 0.0;
  task::PathCommand stream_;
  Eigen::Vector3d start_tcp_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d approach_tcp_ = Eigen::Vector3d::Zero();
};

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) {
    sum += value * value;
  }
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

SurfaceFollowingRow measure(const Condition& condition, const SimLog& log,
                            const SurfaceCommand& command, const task::Path& tip_path,
                            const std::filesystem::path& trace_file) {
  SurfaceFollowingRow row;
  row.condition = condition.name;
  std::vector<double> lateral, tangential, total, force;
  std::size_t in_contact = 0;
  // A force sensor's view: a 20 ms moving average (see averagedContactForce()).
  const std::vector<Eigen::Vector3d> averaged_force = averagedContactForce(log, 20);
  std::ofstream trace(trace_file);
  trace << "time_s,tip_x,tip_y,tip_z,nominal_x,nominal_y,lateral_mm,tangential_mm,force_n\n";
  for (std::size_t row_index = 0; row_index < log.size(); ++row_index) {
    const double t = log.time_s[row_index];
    const Eigen::Vector3d tip =
        log.tcp_position[row_index] +
        log.tcp_orientation[row_index] * Eigen::Vector3d(0, 0, kProbeLength);
    const double contact_n = averaged_force[row_index].norm();
    const bool traversing = t >= command.traverseStart() && t <= command.traverseEnd();
    const double s =
        std::clamp((t - command.traverseStart()) * command.speed(), 0.0, tip_path.length());
    const Eigen::Vector3d nominal = tip_path.position(s);
    const Eigen::Vector3d error = tip - nominal;
    const double lateral_m = error.dot(outwardNormal(nominal.x()));
    const double tangential_m = error.dot(tip_path.tangent(s));
    trace << t << ',' << tip.x() << ',' << tip.y() << ',' << tip.z() << ',' << nominal.x() << ','
          << nominal.y() << ',' << 1e3 * lateral_m << ',' << 1e3 * tangential_m << ',' << contact_n
          << '\n';
    if (!traversing) {
      continue;
    }
    lateral.push_back(lateral_m);
    tangential.push_back(tangential_m);
    total.push_back(error.norm());
    force.push_back(contact_n);
    in_contact += contact_n > kContactForceN ? 1 : 0;
    double closest = 1e9;
    for (double along = 0.0; along <= tip_path.length(); along += 5e-4) {
      closest = std::min(closest, (tip - tip_path.position(along)).norm());
    }
    row.max_distance_mm = std::max(row.max_distance_mm, 1e3 * closest);
    row.lateral_max_mm = std::max(row.lateral_max_mm, 1e3 * std::abs(lateral_m));
  }
  row.lateral_rms_mm = 1e3 * rms(lateral);
  row.tangential_rms_mm = 1e3 * rms(tangential);
  row.total_rmse_mm = 1e3 * rms(total);
  double mean = 0.0;
  for (const double value : force) {
    mean += value / static_cast<double>(force.size());
  }
  double variance = 0.0;
  for (const double value : force) {
    variance += (value - mean) * (value - mean) / static_cast<double>(force.size());
  }
  row.force_mean_n = mean;
  row.force_sd_n = std::sqrt(variance);
  row.contact_fraction =
      force.empty() ? 0.0 : static_cast<double>(in_contact) / static_cast<double>(force.size());
  return row;
}

nlohmann::json toJson(const SurfaceFollowingRow& row) {
  return {{"condition", row.condition},
          {"lateral_rms_mm", row.lateral_rms_mm},
          {"lateral_max_mm", row.lateral_max_mm},
          {"tangential_rms_mm", row.tangential_rms_mm},
          {"total_rmse_mm", row.total_rmse_mm},
          {"max_distance_mm", row.max_distance_mm},
          {"force_mean_n", row.force_mean_n},
          {"force_sd_n", row.force_sd_n},
          {"contact_fraction", row.contact_fraction}};
}

}  // namespace

std::vector<SurfaceFollowingRow> runSurfaceFollowing(const SurfaceFollowingOptions& options) {
  if (!(options.speed_m_per_s > 0.0) ||
      !(options.path_fraction > 0.0 && options.path_fraction <= 1.0)) {
    throw std::runtime_error(
        "surface-following: speed must be > 0 and the path fraction in (0, 1]");
  }
  std::filesystem::create_directories(options.out_dir);
  const TcpPose home = homeTcpPose("fr3");

  const task::Path tip_path(nominalTipPoints(options.path_fraction));
  {
    std::ofstream fixture(options.out_dir / "fixture.csv");
    fixture << "x,face_y,face_y_displaced\n";
    const Eigen::Vector2d pivot(kPathStartX + 0.5 * kPathLengthX, 0.0);
    for (int i = 0; i <= 200; ++i) {
      const double x = kPathStartX - 0.04 + (kPathLengthX + 0.08) * i / 200.0;
      const Eigen::Vector2d moved =
          Eigen::Rotation2Dd(kDisplacementYawRad) * (Eigen::Vector2d(x, faceY(x)) - pivot) + pivot +
          Eigen::Vector2d(0.0, kDisplacementY);
      fixture << x << ',' << faceY(x) << ',' << moved.y() << '\n';
    }
  }

  const std::vector<Condition> conditions{{"fixed_frame", false, false},
                                          {"task_aligned", true, false},
                                          {"task_aligned_displaced", true, true}};
  std::vector<SurfaceFollowingRow> rows;
  for (const Condition& condition : conditions) {
    const std::filesystem::path folder = options.out_dir / condition.name;
    std::filesystem::create_directories(folder);
    const std::filesystem::path fixture_file = folder / "fixture.xml";
    std::ofstream(fixture_file) << fixtureFragment(condition.displaced ? kDisplacementY : 0.0,
                                                   condition.displaced ? kDisplacementYawRad : 0.0);

    SimRunOptions run;
    run.config = simControllerConfig(
        "fr3", "",
        (std::filesystem::path(COMPLY_SOURCE_DIR) / "config/sim/cartesian_impedance.yaml")
            .string());
    // Within reach of the pressing reference, which lies 100 mm inside the fixture.
    run.config.validation.max_position_jump_m = 0.15;
    const int dof = run.config.dof;
    SurfaceCommand command(condition, home.position, home.orientation, options.speed_m_per_s,
                           options.path_fraction, dof);
    run.task = parseTaskFile(
        "task:\n  command_rate_hz: 100\n  scene: {tool: probe_tool.xml, substeps: 2}\n"
        "  camera: {lookat: [0.42, 0.0, 0.3], distance_m: 1.4, azimuth_deg: 110, "
        "elevation_deg: -35}\n  waypoints: [{time_s: " +
            std::to_string(command.traverseEnd()) + "}]\n",
        "surface-following task", std::filesystem::path(COMPLY_SOURCE_DIR) / "examples" / "sim",
        true, dof);
    run.task.scene.objects.push_back(fixture_file);
    run.duration_s = command.duration();
    run.out_dir = folder;
    run.snapshots = options.pictures;
    run.progress = options.progress;
    run.cartesian_source = std::make_shared<task::FunctionSource<CartesianCommand>>(
          [&command](double t, const MeasuredPose&) { return command(t); });
    const SimResult result = runSimulation(run);
    if (result.summary.faults > 0) {
      throw std::runtime_error("surface-following " + condition.name +
                               ": controller FAULT: " + result.summary.messages.back());
    }
    rows.push_back(measure(condition, result.log, command, tip_path, folder / "trace.csv"));
  }

  nlohmann::json results = nlohmann::json::array();
  for (const SurfaceFollowingRow& row : rows) {
    results.push_back(toJson(row));
  }
  std::ofstream(options.out_dir / "results.json") << results.dump(2) << "\n";
  std::ofstream table(options.out_dir / "table.md");
  printSurfaceFollowingTable(rows, table);
  if (options.pictures) {
    const std::string command =
        "/usr/bin/python3 " +
        (std::filesystem::path(COMPLY_SOURCE_DIR) / "scripts" / "plot_surface_following.py")
            .string() +
        " '" + options.out_dir.string() + "' > /dev/null 2>&1";
    if (std::system(command.c_str()) != 0 && options.progress != nullptr) {
      *options.progress << "surface-following: warning: the plot script failed\n";
    }
  }
  return rows;
}

void printSurfaceFollowingTable(const std::vector<SurfaceFollowingRow>& rows, std::ostream& out) {
  // The paper's FR3 numbers (fixed-frame -> task-aligned), DESIGN.md.
  out << "| metric | paper fixed | paper aligned |";
  for (const SurfaceFollowingRow& row : rows) {
    out << ' ' << row.condition << " |";
  }
  out << "\n|---|---|---|";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out << "---|";
  }
  out << "\n" << std::fixed << std::setprecision(1);
  const auto line = [&](const char* name, const char* paper_fixed, const char* paper_aligned,
                        double SurfaceFollowingRow::*field, int precision) {
    out << "| " << name << " | " << paper_fixed << " | " << paper_aligned << " |";
    for (const SurfaceFollowingRow& row : rows) {
      out << ' ' << std::setprecision(precision) << row.*field << " |";
    }
    out << "\n";
  };
  line("lateral RMS [mm]", "16.3", "7.4", &SurfaceFollowingRow::lateral_rms_mm, 1);
  line("lateral max [mm]", "40.4", "13.7", &SurfaceFollowingRow::lateral_max_mm, 1);
  line("tangential RMS [mm]", "101.7", "18.8", &SurfaceFollowingRow::tangential_rms_mm, 1);
  line("total RMSE [mm]", "103.0", "20.2", &SurfaceFollowingRow::total_rmse_mm, 1);
  line("max distance to path [mm]", "-", "-", &SurfaceFollowingRow::max_distance_mm, 1);
  line("contact force mean [N]", "5.22", "5.07", &SurfaceFollowingRow::force_mean_n, 2);
  line("contact force SD [N]", "1.49", "1.30", &SurfaceFollowingRow::force_sd_n, 2);
  line("in contact [share]", "-", "-", &SurfaceFollowingRow::contact_fraction, 3);
}

int surfaceFollowingCommand(const SurfaceFollowingOptions& options, std::ostream& out,
                            std::ostream& err) {
  SurfaceFollowingOptions run = options;
  run.progress = &err;
  const std::vector<SurfaceFollowingRow> rows = runSurfaceFollowing(run);
  printSurfaceFollowingTable(rows, out);
  out << "results in " << std::filesystem::absolute(options.out_dir).string()
      << " (results.json, table.md, surface_following.png, one folder per condition)\n";
  return 0;
}

}  // namespace comply::app
