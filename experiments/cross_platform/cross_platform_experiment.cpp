#include "cross_platform/cross_platform_experiment.hpp"

#include <iostream>
#include <ostream>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/plot_script.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/host/task_file.hpp"
#include "comply/sim/image.hpp"
#include "source_dir.hpp"

namespace comply::experiments {
namespace {

constexpr double kReachedPositionMm = 2.0;
constexpr double kReachedOrientationDeg = 1.0;

bool reached(const CrossPlatformRow& row) {
  return row.position_error_mm <= kReachedPositionMm &&
         row.orientation_error_deg <= kReachedOrientationDeg && row.faults == 0;
}

/// One robot's run into <out>/<robot>/, with its plot when pictures are on.
host::SimResult runRobot(const std::string& robot, OutputMode mode,
                         const CrossPlatformOptions& options,
                         const std::filesystem::path& config_file,
                         const std::filesystem::path& task_file) {
  host::SimRunOptions run;
  run.config = host::simControllerConfig(robot, "", config_file.string());
  run.config.output.mode = mode;
  run.task = host::loadTaskFile(task_file, true, run.config.dof,
                                run.config.validation.quaternion_tolerance);
  run.duration_s = options.duration_s;
  run.out_dir = options.out_dir /
                (mode == OutputMode::kTorque ? robot : robot + "-" + std::string(toString(mode)));
  run.snapshots = options.pictures;
  run.progress = options.progress;
  host::SimResult result = host::runSimulation(run);
  if (options.pictures) {
    host::runPlotScript("plot_sim_log.py",
                        {(run.out_dir / "log.csv").string(), (run.out_dir / "plot.png").string()},
                        options.progress != nullptr ? *options.progress : std::cerr);
  }
  return result;
}

CrossPlatformRow rowOf(const host::SimSummary& summary) {
  return CrossPlatformRow{summary.robot,
                          summary.output_mode,
                          summary.dof,
                          summary.final_position_error_mm,
                          summary.final_orientation_error_deg,
                          summary.settle_time_s,
                          summary.max_torque_nm,
                          summary.rejections,
                          summary.faults};
}

}  // namespace

std::vector<CrossPlatformRow> runCrossPlatform(const CrossPlatformOptions& options) {
  const std::filesystem::path config_file =
      sourcePathOr(options.config_file, "config/sim/cartesian_impedance.yaml");
  const std::filesystem::path task_file =
      sourcePathOr(options.task_file, "examples/sim/cross_platform.yaml");
  makeOutputFolder(options.out_dir);  // its parent must exist

  std::vector<CrossPlatformRow> rows;
  std::vector<sim::Image> pictures;
  for (const std::string& robot : options.robots) {
    const host::SimResult result =
        runRobot(robot, OutputMode::kTorque, options, config_file, task_file);
    const std::filesystem::path end_picture = options.out_dir / robot / "end.png";
    if (options.pictures && std::filesystem::exists(end_picture)) {
      pictures.push_back(sim::readPng(end_picture));
    }
    rows.push_back(rowOf(result.summary));
  }
  if (!options.modes_robot.empty()) {
    for (const OutputMode mode : options.other_modes) {
      rows.push_back(
          rowOf(runRobot(options.modes_robot, mode, options, config_file, task_file).summary));
    }
  }
  writeResults(crossPlatformTable(rows), options.out_dir);
  if (!pictures.empty()) {
    sim::writePng(sim::sideBySide(pictures), options.out_dir / "cross_platform.png");
  }
  return rows;
}

ResultsTable crossPlatformTable(const std::vector<CrossPlatformRow>& rows) {
  ResultsTable table;
  table.columns = {
      Column("robot", "robot"),
      Column("output", "drives"),
      Column("dof", "DOF"),
      Column("position_error_mm", "position error", "mm", 3),
      Column("orientation_error_deg", "orientation error", "deg", 3),
      Column("settle_time_s", "settle time", "s", 2).missingAs("not settled"),
      Column("peak_torque_nm", "peak torque", "N m", 1),
      Column("rejections", "rejections").jsonOnly(),
      Column("faults", "faults").jsonOnly(),
  };
  for (const CrossPlatformRow& row : rows) {
    table.rows.push_back({row.robot, std::string(toString(row.output)), std::int64_t{row.dof},
                          row.position_error_mm, row.orientation_error_deg, row.settle_time_s,
                          row.peak_torque_nm, static_cast<std::int64_t>(row.rejections),
                          static_cast<std::int64_t>(row.faults)});
  }
  return table;
}

int crossPlatformCommand(const CrossPlatformOptions& options, std::ostream& out,
                         std::ostream& err) {
  CrossPlatformOptions run = options;
  run.progress = &err;
  const std::vector<CrossPlatformRow> rows = runCrossPlatform(run);
  writeMarkdownTable(crossPlatformTable(rows), out);
  bool all_reached = true;
  for (const CrossPlatformRow& row : rows) {
    if (!reached(row)) {
      err << "comply experiment cross-platform: " << row.robot << " (" << toString(row.output)
          << " drives) did not reach the target "
          << "within " << kReachedPositionMm << " mm / " << kReachedOrientationDeg << " deg\n";
      all_reached = false;
    }
  }
  out << "results in " << std::filesystem::absolute(options.out_dir).string()
      << " (results.json, table.md, cross_platform.png, one folder per robot)\n";
  return all_reached ? 0 : 1;
}

}  // namespace comply::experiments
