#include "connector_mating/connector_mating_experiment.hpp"

#include <cmath>
#include <fstream>
#include <ostream>
#include <sstream>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/host/task_file.hpp"
#include "connector_mating/mating_stream.hpp"
#include "connector_mating/peg_and_socket.hpp"
#include "connector_mating/trial_evaluation.hpp"
#include "source_dir.hpp"

namespace comply::experiments {
namespace {

using connector_mating::ComplianceFrame;
using connector_mating::MatingStream;
using connector_mating::Trial;

/// The task around the stream: scene, camera, and the waypoint the settle time counts from.
host::TaskFile matingTask(double motion_end_s, const std::filesystem::path& out_dir, int dof) {
  return host::parseTaskFile(
      "task:\n  command_rate_hz: 100\n  scene: {substeps: 4}\n  camera: {lookat: [0.45, 0.0, "
      "0.22], distance_m: 0.5, azimuth_deg: 90, elevation_deg: -15}\n  waypoints: "
      "[{time_s: " +
          std::to_string(motion_end_s) + "}]\n",
      "connector-mating task", out_dir, true, dof);
}

pipeline::WrapperConfig trialConfig(const Trial& trial) {
  pipeline::WrapperConfig config = host::simControllerConfig(
      "fr3", "", sourcePath("config/sim/cartesian_impedance.yaml").string());
  if (trial.frame == ComplianceFrame::kMeasuredTcp) {
    plugin::ParameterValue reference;
    reference.text = "tcp";
    reference.is_text = true;
    config.plugin_parameters["task_frame_reference"] = reference;
  }
  return config;
}

/// One trial's run into <out>/<condition>_<offset>deg/.
ConnectorMatingRow runTrial(const Trial& trial, double offset_deg,
                            const ConnectorMatingOptions& options, const host::TcpPose& home,
                            const std::filesystem::path& peg_file) {
  std::ostringstream name;
  name << trial.condition << "_" << offset_deg << "deg";
  const std::filesystem::path folder = options.out_dir / name.str();
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "socket.xml") << connector_mating::socketFragment(trial.offset_rad);

  host::SimRunOptions run;
  run.config = trialConfig(trial);
  MatingStream stream(trial, home.position, home.orientation,
                      options.rotational_stiffness_nm_per_rad, run.config.dof);
  if (options.nullspace_stiffness_nm_per_rad) {
    stream.overrideNullspace(*options.nullspace_stiffness_nm_per_rad);
  }
  run.task = matingTask(stream.motionEndTime(), options.out_dir, run.config.dof);
  run.task.scene.tool = peg_file;
  run.task.scene.objects.push_back(folder / "socket.xml");
  run.duration_s = MatingStream::duration();
  run.out_dir = folder;
  run.snapshots = options.pictures;
  run.progress = options.progress;
  run.plant_friction_scale = options.plant_friction_scale;
  run.cartesian_source = &stream;
  const host::SimResult result = host::runSimulation(run);
  return connector_mating::evaluateTrial(trial, result.log, stream, options.axial_force_limit_n,
                                         folder / "trace.csv");
}

}  // namespace

std::vector<ConnectorMatingRow> runConnectorMating(const ConnectorMatingOptions& options) {
  makeOutputFolder(options.out_dir);  // its parent must exist
  const host::TcpPose home = host::homeTcpPose("fr3");
  const std::filesystem::path peg_file = options.out_dir / "peg.xml";
  std::ofstream(peg_file) << connector_mating::pegFragment();

  // Refuse an unknown condition before the first trial rather than after minutes of others.
  for (const std::string& condition : options.conditions) {
    connector_mating::trialOf(condition, 0.0);
  }
  std::vector<ConnectorMatingRow> rows;
  for (const double offset_deg : options.offsets_deg) {
    for (const std::string& condition : options.conditions) {
      const Trial trial = connector_mating::trialOf(condition, offset_deg * M_PI / 180.0);
      rows.push_back(runTrial(trial, offset_deg, options, home, peg_file));
    }
  }
  writeResultsAndPlots(connectorMatingTable(rows), options.out_dir, "plot_connector_mating.py",
                       options.pictures, options.progress);
  return rows;
}

ResultsTable connectorMatingTable(const std::vector<ConnectorMatingRow>& rows) {
  ResultsTable table;
  table.columns = {
      Column("offset_deg", "offset", "deg", 0),
      Column("condition", "condition"),
      Column("seated", "seated"),
      Column("depth_mm", "depth", "mm", 1),
      Column("peak_axial_force_n", "peak axial force", "N", 1),
      Column("seat_time_s", "seat time", "s", 2),
      Column("task_axis_to_socket_deg", "task z to socket axis", "deg", 1),
      Column("peg_to_socket_deg", "peg to socket axis", "deg", 1),
      Column("failure", "failure"),
  };
  for (const ConnectorMatingRow& row : rows) {
    // NaN seat time (not seated) and no failure (seated) are "no value": null and "-".
    table.rows.push_back({row.offset_deg, row.condition, row.seated, row.depth_mm,
                          row.peak_axial_force_n, row.seat_time_s, row.task_axis_to_socket_deg,
                          row.peg_to_socket_deg,
                          row.failure.empty() ? Value{} : Value{row.failure}});
  }
  return table;
}

int connectorMatingCommand(const ConnectorMatingOptions& options, std::ostream& out,
                           std::ostream& err) {
  printResults(connectorMatingTable(runConnectorMating(withProgress(options, err))),
               options.out_dir, "", out);
  return 0;
}

}  // namespace comply::experiments
