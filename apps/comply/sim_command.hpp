#pragma once
// `comply sim`: a compliant controller on a simulated arm, headless; leaves a CSV log, PNG
// snapshots and a plot of tracking error and torque in --out.

#include <filesystem>
#include <iosfwd>
#include <string>

#include "comply/host/task_file.hpp"

namespace comply::app {

struct SimOptions {
  std::string robot;        ///< name or folder; overrides the config's robot
  std::string plugin;       ///< without --config: the plugin (default cartesian_impedance)
  std::string config_file;  ///< controller YAML
  std::string task_file;
  std::string out_dir;              ///< default out/sim-<robot>
  std::string record_path;          ///< non-empty: an MCAP recording of the run
  double duration_s = 0.0;          ///< 0: the task's
  double snapshot_every_ms = -1.0;  ///< < 0: the task's
  std::string foxglove;             ///< non-empty: a Foxglove live view on [ADDRESS:]PORT
  double foxglove_wait_s = 0;       ///< wait this long for the first viewer
  bool realtime = false;
  bool view = false;
  bool plot = true;
};

/// Runs it; returns the exit code (0 ok, 1 the controller faulted, 2 bad input).
int simCommand(const SimOptions& options, std::ostream& out, std::ostream& err);

/// Draws `csv` (a `comply sim` log) into `png` with the project's plotting script. Returns false
/// and says why on `err` when python3 with matplotlib is missing or the script fails.
bool plotLog(const std::filesystem::path& csv, const std::filesystem::path& png, std::ostream& err);

}  // namespace comply::app
