#include "surface_following/surface_following_experiment.hpp"

#include <fstream>
#include <ostream>
#include <stdexcept>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/host/task_file.hpp"
#include "comply/task/path.hpp"
#include "source_dir.hpp"
#include "surface_following/fixture.hpp"
#include "surface_following/surface_stream.hpp"
#include "surface_following/tracking_metrics.hpp"

namespace comply::experiments {
namespace {

using surface_following::SurfaceCondition;
using surface_following::SurfaceStream;

/// The task around the stream: scene, camera, and the waypoint the settle time counts from.
host::TaskFile surfaceTask(double motion_end_s, int dof) {
  return host::parseTaskFile(
      "task:\n  command_rate_hz: 100\n  scene: {tool: probe_tool.xml, substeps: 2}\n"
      "  camera: {lookat: [0.42, 0.0, 0.3], distance_m: 1.4, azimuth_deg: 110, "
      "elevation_deg: -35}\n  waypoints: [{time_s: " +
          std::to_string(motion_end_s) + "}]\n",
      "surface-following task", sourcePath("examples/sim"), true, dof);
}

/// One condition's run into <out>/<condition>/, measured against `tip_path`.
SurfaceFollowingRow runCondition(const SurfaceCondition& condition,
                                 const SurfaceFollowingOptions& options, const host::TcpPose& home,
                                 const task::Path& tip_path) {
  const std::filesystem::path folder = options.out_dir / condition.name;
  std::filesystem::create_directories(folder);
  const std::filesystem::path fixture_file = folder / "fixture.xml";
  std::ofstream(fixture_file) << surface_following::fixtureFragment(
      condition.displaced ? surface_following::kDisplacementY : 0.0,
      condition.displaced ? surface_following::kDisplacementYawRad : 0.0);

  host::SimRunOptions run;
  run.config = host::simControllerConfig(
      "fr3", "", sourcePath("config/sim/cartesian_impedance.yaml").string());
  // Within reach of the pressing reference, which lies 100 mm inside the fixture.
  run.config.validation.max_position_jump_m = 0.15;
  if (condition.force) {
    run.config.force_control.source = condition.source == "observer"
                                          ? pipeline::ForceSource::kObserver
                                          : pipeline::ForceSource::kSensor;
    run.config.observer.enabled = condition.source == "observer";
    // The sensor's reading chatters with MuJoCo's rigid contact at the physics step.
    run.config.wrench_sensor.filter_hz = 50.0;
    // On the commanded torque the observer would count the joints' friction as contact (several
    // newtons at the TCP once the joints move); the FR3 measures its joint torques on the link
    // side of the friction, and so does the plant here.
    run.config.observer.measured_torque = true;
    run.plant_link_side_torque = true;
    // The probe is the tool beyond the wrist sensor: declared, its weight is compensated and comes
    // off the sensor's reading.
    run.config.payload_compensation = true;
    run.config.payload.mass_kg = surface_following::kProbeMassKg;
    run.config.payload.com_in_tip = Eigen::Vector3d(0.0, 0.0, surface_following::kProbeComM);
  }
  SurfaceStream stream(condition, home.position, home.orientation, options.speed_m_per_s,
                       options.path_fraction, run.config.dof);
  run.task = surfaceTask(stream.motionEndTime(), run.config.dof);
  run.task.scene.objects.push_back(fixture_file);
  run.duration_s = stream.duration();
  run.out_dir = folder;
  run.snapshots = options.pictures;
  run.progress = options.progress;
  run.cartesian_source = &stream;
  const host::SimResult result = host::runSimulation(run);
  if (result.summary.faults > 0) {
    throw std::runtime_error("surface-following " + condition.name +
                             ": controller FAULT: " + result.summary.fault_reason);
  }
  return surface_following::measureTracking(condition.name, result.log, stream, tip_path,
                                            folder / "trace.csv");
}

}  // namespace

std::vector<SurfaceFollowingRow> runSurfaceFollowing(const SurfaceFollowingOptions& options) {
  if (!(options.speed_m_per_s > 0.0) ||
      !(options.path_fraction > 0.0 && options.path_fraction <= 1.0)) {
    throw std::runtime_error(
        "surface-following: speed must be > 0 and the path fraction in (0, 1]");
  }
  makeOutputFolder(options.out_dir);  // its parent must exist
  const host::TcpPose home = host::homeTcpPose("fr3");
  const task::Path tip_path(surface_following::nominalTipPoints(options.path_fraction));
  surface_following::writeFixtureCsv(options.out_dir / "fixture.csv");

  const std::vector<SurfaceCondition> conditions{
      {"fixed_frame", false, false},
      {"task_aligned", true, false},
      {"task_aligned_displaced", true, true},
      {"force_sensor", true, false, true, "sensor"},
      {"force_observer", true, false, true, "observer"},
      {"force_sensor_displaced", true, true, true, "sensor"}};
  std::vector<SurfaceFollowingRow> rows;
  for (const SurfaceCondition& condition : conditions) {
    rows.push_back(runCondition(condition, options, home, tip_path));
  }
  writeResultsAndPlots(surfaceFollowingTable(rows), options.out_dir, "plot_surface_following.py",
                       options.pictures, options.progress);
  return rows;
}

ResultsTable surfaceFollowingTable(const std::vector<SurfaceFollowingRow>& rows) {
  ResultsTable table;
  // The paper's FR3 numbers (fixed-frame, task-aligned), as README.md (Evaluation) quotes them.
  table.transposed = ResultsTable::Transposed{.corner = "metric",
                                              .label_key = "condition",
                                              .reference_titles = {"paper fixed", "paper aligned"}};
  const auto metric = [](const char* key, const char* title, const char* unit, int precision,
                         const char* paper_fixed, const char* paper_aligned) {
    return Column(key, title, unit, precision).withReference({paper_fixed, paper_aligned});
  };
  table.columns = {
      Column("condition", "condition"),
      metric("lateral_rms_mm", "lateral RMS", "mm", 1, "16.3", "7.4"),
      metric("lateral_max_mm", "lateral max", "mm", 1, "40.4", "13.7"),
      metric("tangential_rms_mm", "tangential RMS", "mm", 1, "101.7", "18.8"),
      metric("total_rmse_mm", "total RMSE", "mm", 1, "103.0", "20.2"),
      metric("max_distance_mm", "max distance to path", "mm", 1, "-", "-"),
      metric("force_mean_n", "contact force mean", "N", 2, "5.22", "5.07"),
      metric("force_sd_n", "contact force SD", "N", 2, "1.49", "1.30"),
      metric("contact_fraction", "in contact", "share", 3, "-", "-"),
      metric("normal_force_rmse_n", "normal force RMSE (5 N target)", "N", 2, "-", "-"),
      metric("normal_force_rms_percent", "normal force RMS error", "%", 1, "-", "-"),
  };
  for (const SurfaceFollowingRow& row : rows) {
    table.rows.push_back({row.condition, row.lateral_rms_mm, row.lateral_max_mm,
                          row.tangential_rms_mm, row.total_rmse_mm, row.max_distance_mm,
                          row.force_mean_n, row.force_sd_n, row.contact_fraction,
                          row.normal_force_rmse_n, row.normal_force_rms_percent});
  }
  return table;
}

int surfaceFollowingCommand(const SurfaceFollowingOptions& options, std::ostream& out,
                            std::ostream& err) {
  printResults(surfaceFollowingTable(runSurfaceFollowing(withProgress(options, err))),
               options.out_dir,
               "results.json, table.md, surface_following.png, one folder per condition", out);
  return 0;
}

}  // namespace comply::experiments
