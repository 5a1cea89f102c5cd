#include "cross_platform_experiment.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <ostream>

#include "comply/sim/image.hpp"
#include "controller_setup.hpp"
#include "sim_command.hpp"
#include "sim_session.hpp"

namespace comply::app {
namespace {

constexpr double kReachedPositionMm = 2.0;
constexpr double kReachedOrientationDeg = 1.0;

std::filesystem::path sourcePath(const std::filesystem::path& given, const char* fallback) {
  return given.empty() ? std::filesystem::path(COMPLY_SOURCE_DIR) / fallback : given;
}

nlohmann::json toJson(const CrossPlatformRow& row) {
  const auto number = [](double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  return {{"robot", row.robot},
          {"dof", row.dof},
          {"position_error_mm", number(row.position_error_mm)},
          {"orientation_error_deg", number(row.orientation_error_deg)},
          {"settle_time_s", number(row.settle_time_s)},
          {"peak_torque_nm", number(row.peak_torque_nm)},
          {"rejections", row.rejections},
          {"faults", row.faults}};
}

bool reached(const CrossPlatformRow& row) {
  return row.position_error_mm <= kReachedPositionMm &&
         row.orientation_error_deg <= kReachedOrientationDeg && row.faults == 0;
}

}  // namespace

std::vector<CrossPlatformRow> runCrossPlatform(const CrossPlatformOptions& options) {
  const std::filesystem::path config_file =
      sourcePath(options.config_file, "config/sim/cartesian_impedance.yaml");
  const std::filesystem::path task_file =
      sourcePath(options.task_file, "examples/sim/cross_platform.yaml");
  std::filesystem::create_directories(options.out_dir);

  std::vector<CrossPlatformRow> rows;
  std::vector<sim::Image> pictures;
  for (const std::string& robot : options.robots) {
    SimRunOptions run;
    run.config = simControllerConfig(robot, "", config_file.string());
    run.task =
        loadTaskFile(task_file, true, run.config.dof, run.config.validation.quaternion_tolerance);
    run.duration_s = options.duration_s;
    run.out_dir = options.out_dir / robot;
    run.snapshots = options.pictures;
    run.progress = options.progress;
    const SimResult result = runSimulation(run);
    if (options.pictures) {
      plotLog(run.out_dir / "log.csv", run.out_dir / "plot.png",
              options.progress != nullptr ? *options.progress : std::cerr);
      if (std::filesystem::exists(run.out_dir / "end.png")) {
        pictures.push_back(sim::readPng(run.out_dir / "end.png"));
      }
    }
    const SimSummary& summary = result.summary;
    rows.push_back(CrossPlatformRow{summary.robot, summary.dof, summary.final_position_error_mm,
                                    summary.final_orientation_error_deg, summary.settle_time_s,
                                    summary.max_torque_nm, summary.rejections, summary.faults});
  }

  nlohmann::json results = nlohmann::json::array();
  for (const CrossPlatformRow& row : rows) {
    results.push_back(toJson(row));
  }
  std::ofstream(options.out_dir / "results.json") << results.dump(2) << "\n";
  std::ofstream table(options.out_dir / "table.md");
  printCrossPlatformTable(rows, table);
  if (!pictures.empty()) {
    sim::writePng(sim::sideBySide(pictures), options.out_dir / "cross_platform.png");
  }
  return rows;
}

void printCrossPlatformTable(const std::vector<CrossPlatformRow>& rows, std::ostream& out) {
  out << "| robot | DOF | position error [mm] | orientation error [deg] | settle time [s] | "
         "peak torque [N m] |\n|---|---|---|---|---|---|\n";
  out << std::fixed;
  for (const CrossPlatformRow& row : rows) {
    out << "| " << row.robot << " | " << row.dof << " | " << std::setprecision(3)
        << row.position_error_mm << " | " << row.orientation_error_deg << " | ";
    if (std::isnan(row.settle_time_s)) {
      out << "not settled";
    } else {
      out << std::setprecision(2) << row.settle_time_s;
    }
    out << " | " << std::setprecision(1) << row.peak_torque_nm << " |\n";
  }
}

int crossPlatformCommand(const CrossPlatformOptions& options, std::ostream& out,
                         std::ostream& err) {
  CrossPlatformOptions run = options;
  run.progress = &err;
  const std::vector<CrossPlatformRow> rows = runCrossPlatform(run);
  printCrossPlatformTable(rows, out);
  bool all_reached = true;
  for (const CrossPlatformRow& row : rows) {
    if (!reached(row)) {
      err << "comply experiment cross-platform: " << row.robot << " did not reach the target "
          << "within " << kReachedPositionMm << " mm / " << kReachedOrientationDeg << " deg\n";
      all_reached = false;
    }
  }
  out << "results in " << std::filesystem::absolute(options.out_dir).string()
      << " (results.json, table.md, cross_platform.png, one folder per robot)\n";
  return all_reached ? 0 : 1;
}

}  // namespace comply::app
