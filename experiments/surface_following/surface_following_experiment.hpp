#pragma once
// `comply experiment surface-following`: a probe on the FR3 follows the curved face of a rigid
// D-shaped fixture (30 mm lateral deviation over a 180 mm path) while pressing on it through a
// compliant axis. Condition A (fixed-frame): 50 N/m along base y, 1000 N/m along x and z.
// Condition B (task-aligned): 50 N/m along the local surface normal, 1000 N/m tangentially and
// vertically, the task frame (Darboux: tangent, normal, vertical) updated with every command
// from the fixture geometry. Both get the same position command: the nominal contact path pushed
// 100 mm into the surface along its normal (5 N at 50 N/m). A third run displaces the fixture
// (controller and command unchanged) and must keep contact. Three more replace the spring along
// the normal by force control with a 5 N target (pipeline/force_axes.hpp): reading the wrist
// sensor, reading the momentum observer, and the sensor on the displaced fixture.

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "results_writer.hpp"

namespace comply::experiments {

struct SurfaceFollowingOptions {
  std::filesystem::path out_dir = "out/surface-following";
  double speed_m_per_s = 0.02;  ///< traverse speed; the full path takes 9 s at 0.02 m/s
  double path_fraction = 1.0;   ///< < 1: traverse only this share of the path (short test runs)
  bool pictures = true;
  std::ostream* progress = nullptr;
};

struct SurfaceFollowingRow {
  std::string condition;        ///< fixed_frame, task_aligned, task_aligned_displaced
  double lateral_rms_mm = 0.0;  ///< along the local surface normal, tip vs nominal path
  double lateral_max_mm = 0.0;
  double tangential_rms_mm = 0.0;  ///< along the path tangent
  double total_rmse_mm = 0.0;
  double max_distance_mm = 0.0;  ///< largest tip distance from the nominal path (closest point)
  double force_mean_n = 0.0;     ///< contact force magnitude during the traverse
  double force_sd_n = 0.0;
  double contact_fraction = 0.0;  ///< share of traverse cycles with contact force > 0.5 N
  /// The normal component (along the face's normal) against kNormalForceN, during the traverse.
  double normal_force_rmse_n = 0.0;
  double normal_force_rms_percent = 0.0;
};

/// Runs the three conditions; writes <out>/<condition>/ (log, snapshots, trace), <out>/fixture.csv,
/// <out>/results.json, <out>/table.md and, with pictures, <out>/surface_following.png.
std::vector<SurfaceFollowingRow> runSurfaceFollowing(const SurfaceFollowingOptions& options);

/// The rows as table.md (one column per condition, beside the paper's) and results.json show them.
ResultsTable surfaceFollowingTable(const std::vector<SurfaceFollowingRow>& rows);

/// The command line: returns 0 (a controller fault throws).
int surfaceFollowingCommand(const SurfaceFollowingOptions& options, std::ostream& out,
                            std::ostream& err);

}  // namespace comply::experiments
