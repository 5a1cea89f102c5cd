#pragma once
// `comply experiment cross-platform`: the same Cartesian plugin, the same controller file and the
// same command drive FR3, LBR iiwa14, Rizon 4s and UR5e to one common task-space target; only the
// URDF, joint/frame names (robot.yaml) differ. Writes a table, results.json and one PNG with the
// robots side by side.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "comply/core/actuator_command.hpp"
#include "comply/model/robot_description.hpp"
#include "results_writer.hpp"

namespace comply::experiments {

struct CrossPlatformOptions {
  std::vector<std::string> robots = model::availableRobots();  ///< default: every robot
  std::filesystem::path config_file;  ///< default config/sim/cartesian_impedance.yaml
  std::filesystem::path task_file;    ///< default examples/sim/cross_platform.yaml
  std::filesystem::path out_dir = "out/cross-platform";
  /// The same run again on this robot's arm with other drives (output.mode), one row each: a
  /// PD-driven arm, and position- and velocity-controlled arms in admittance. Empty: none.
  std::string modes_robot = "ur5e";
  std::vector<OutputMode> other_modes = {OutputMode::kJointPd, OutputMode::kPosition,
                                         OutputMode::kVelocity};
  double duration_s = 0.0;  ///< 0: the task's
  bool pictures = true;
  std::ostream* progress = nullptr;
};

struct CrossPlatformRow {
  std::string robot;
  OutputMode output = OutputMode::kTorque;  ///< the drives' kind (output.mode)
  int dof = 0;
  double position_error_mm = 0.0;  ///< at the end, vs the common target
  double orientation_error_deg = 0.0;
  double settle_time_s = 0.0;   ///< after the reference stops, to 1 mm / 0.5 deg; NaN: never
  double peak_torque_nm = 0.0;  ///< admittance: the virtual arm's
  std::uint64_t rejections = 0;
  std::uint64_t faults = 0;
};

/// Runs every robot, then modes_robot in each of other_modes; writes <out>/<robot>/ (and
/// <out>/<robot>-<mode>/: log, snapshots, plot), <out>/results.json, <out>/table.md and
/// <out>/cross_platform.png (the torque-driven robots side by side).
std::vector<CrossPlatformRow> runCrossPlatform(const CrossPlatformOptions& options);

/// The rows as table.md and results.json show them.
ResultsTable crossPlatformTable(const std::vector<CrossPlatformRow>& rows);

/// The command line: returns 0 when every robot reached the target within 2 mm / 1 deg, else 1.
int crossPlatformCommand(const CrossPlatformOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::experiments
