#pragma once
// A task file: the commands a simulated run streams over time, and the scene it runs in.
//
//   task:
//     duration_s: 6.0                 # run length (comply sim --duration overrides)
//     command_rate_hz: 100            # how often the reference is streamed
//     scene: {tool: probe.xml, objects: [box.xml], substeps: 2, seed: 0}  # paths: this file's
//     folder camera: {lookat: [0.3, 0, 0.4], distance_m: 2.0, azimuth_deg: 135, elevation_deg: -20}
//     snapshot_every_ms: 0            # 0: start and end only
//     waypoints:
//       - time_s: 0.0                 # gains, task frame, ... apply from this time
//         stiffness_translational: [800, 800, 800]
//       - time_s: 2.0                 # the pose is reached at this time
//         position_offset: [0.1, 0.0, 0.0]   # m, from the start TCP position (or `position`)
//         orientation: [1, 0, 0, 0]          # x y z w, base frame
//         interpolate: linear                # linear (default), smooth or step
//
//     path:                           # optional, Cartesian: stream along a path afterwards
//       start_time_s: 3.0               # leaves the first point at this time
//       speed_m_per_s: 0.02
//       points: [[0.4, 0.0, 0.3], ...]  # m, base frame (TCP), dense enough to be a curve
//       frame: frenet                   # frenet | darboux (with surface_normal) | fixed
//       (task_frame) surface_normal: [0, 0, 1]       # darboux: a plane's outward normal
//       stiffness_translational: [1000, 1000, 50]  # per task axis [N/m]
//       stiffness_rotational: [50, 50, 50]         # per task axis [N m/rad]
//       damping_ratio: 1.0              # critically damped
//       offset: [0, 0, 0]               # reference offset in the task frame [m]
//       orientation: [1, 0, 0, 0]       # TCP orientation held along the path (x y z w)
//
// Waypoint keys besides time_s, interpolate, position, position_offset and orientation are
// command fields with the schema's names (docs/command-schema.md), read once at load. For joint
// control, `position` and `position_offset` are joint vectors [rad | m]. As in the controller YAML,
// a 3x3 gain block may be given as 1 number (isotropic), 3 (diagonal) or 9 (row-major, task frame).
// The reference between two waypoints moves along a straight line (slerp for orientation) with the
// matching velocity feedforward: at a constant speed (linear), or by a minimum-jerk profile that
// starts and ends at rest (smooth: no step in the velocity, so none in the damping's torque).

#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/schema/schema.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/scene_xml.hpp"
#include "comply/task/path_command.hpp"

namespace comply::host {

/// Longest simulated run [s]: the log is kept in memory for the plot, about 0.65 MB per second.
inline constexpr double kMaxSimDurationS = 600.0;

enum class Interpolation { kLinear, kSmooth, kStep };

struct Waypoint {
  double time_s = 0.0;
  Interpolation interpolate = Interpolation::kLinear;
  std::optional<std::vector<double>> position;         ///< Cartesian [m] (3) or joint (dof)
  std::optional<std::vector<double>> position_offset;  ///< from the start, same units
  std::optional<std::vector<double>> orientation;      ///< x y z w (Cartesian only)
  /// The other command fields, typed (the controller's kind); its `fields` are their groups.
  std::variant<CartesianCommand, JointCommand> command;
  schema::FieldSet keys = 0;  ///< which of them the waypoint gives (the rest: the command in force)
};

struct TaskFile {
  std::filesystem::path path;
  double duration_s = 5.0;
  double command_rate_hz = 100.0;
  sim::SceneOptions scene;
  int substeps = 1;
  std::uint64_t seed = 0;
  sim::CameraView camera;
  double snapshot_every_ms = 0.0;
  std::vector<Waypoint> waypoints;  ///< sorted by time_s
  /// Optional (Cartesian only): from path_options.start_time_s on, commands stream along this
  /// path (task::PathCommand) instead of following the waypoints.
  std::optional<std::vector<Eigen::Vector3d>> path_points;
  task::PathCommandOptions path_options;
};

/// Reads and checks a task file: every number finite, quaternions of unit norm (within
/// `quaternion_tolerance`), waypoint times non-decreasing, vectors of the right length for a
/// Cartesian (`cartesian`) or joint controller with `dof` joints. Throws std::runtime_error naming
/// the file, the waypoint and the key.
TaskFile loadTaskFile(const std::filesystem::path& file, bool cartesian, int dof,
                      double quaternion_tolerance = 1e-3);

/// Same from YAML text; relative scene paths resolve against `folder`.
TaskFile parseTaskFile(const std::string& yaml_text, const std::string& source,
                       const std::filesystem::path& folder, bool cartesian, int dof,
                       double quaternion_tolerance = 1e-3);

}  // namespace comply::host
