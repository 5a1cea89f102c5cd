#include "sim_command.hpp"

#include <cstdlib>
#include <iostream>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/plot_script.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/sim/viewer.hpp"

namespace comply::app {

bool plotLog(const std::filesystem::path& csv, const std::filesystem::path& png,
             std::ostream& err) {
  return host::runPlotScript("plot_sim_log.py", {csv.string(), png.string()}, err);
}

int simCommand(const SimOptions& options, std::ostream& out, std::ostream& err) {
  if (options.task_file.empty()) {
    err << "comply sim: --task is required\n";
    return 2;
  }
  // Before anything runs: a long run must not fail at its end for want of a folder.
  if (!options.record_path.empty()) {
    if (const std::string why = missingFolderOf(options.record_path); !why.empty()) {
      err << "comply sim: cannot record to " << options.record_path << ": " << why << "\n";
      return 2;
    }
  }
  if (options.view && !sim::Viewer::displayAvailable()) {
    err << "comply sim: --view needs a display, and none is reachable (DISPLAY and "
           "WAYLAND_DISPLAY are unset or unusable). Run without --view: snapshots and plots go "
           "to --out.\n";
    return 2;
  }
  host::SimRunOptions run;
  if (!options.foxglove.empty()) {
    try {
      run.foxglove = host::parseViewAddress(options.foxglove);
    } catch (const std::invalid_argument& error) {
      err << "comply sim: " << error.what() << "\n";
      return 2;
    }
    run.foxglove_wait_s = options.foxglove_wait_s;
  }
  run.config = host::simControllerConfig(options.robot,
                                         options.plugin.empty() && options.config_file.empty()
                                             ? "cartesian_impedance"
                                             : options.plugin,
                                         options.config_file);
  // Resolved once: the robot, the model and the plugin (whose kind decides the task's commands).
  run.resolved = pipeline::resolveController(run.config);
  run.task = host::loadTaskFile(options.task_file, run.resolved->cartesian(), run.config.dof,
                                run.config.validation.quaternion_tolerance);
  if (options.snapshot_every_ms >= 0.0) {
    run.task.snapshot_every_ms = options.snapshot_every_ms;
  }
  run.duration_s = options.duration_s;
  run.realtime = options.realtime;
  run.view = options.view;
  if (options.out_dir.empty()) {
    makeOutputFolder("out");  // the default's own parent, in the working folder
    run.out_dir = std::filesystem::path("out") / ("sim-" + run.resolved->robot.name);
  } else {
    run.out_dir = options.out_dir;  // made by the run, as its last folder only
  }
  run.progress = &err;
  run.record_path = options.record_path;

  host::SimResult result = host::runSimulation(run);
  if (options.plot) {
    const std::filesystem::path png = run.out_dir / "plot.png";
    if (plotLog(run.out_dir / "log.csv", png, err)) {
      result.summary.files.push_back(png);
    }
  }
  host::printSummary(result.summary, out);
  return host::simExitCode(result.summary);
}

}  // namespace comply::app
