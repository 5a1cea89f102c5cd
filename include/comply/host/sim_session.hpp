#pragma once
// One simulated run: a wrapper (joint or Cartesian, chosen by the plugin) on a SimulatedRobot,
// driven by a task file, logged every cycle. Used by `comply sim`, the experiments and the tests.

#include <filesystem>
#include <iosfwd>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/host/live_view.hpp"
#include "comply/host/task_file.hpp"
#include "comply/host/timing_statistics.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/task/command_source.hpp"

namespace comply::host {

struct SimRunOptions {
  pipeline::WrapperConfig config;  ///< names the robot and the plugin
  /// `config` already resolved (robot, model, plugin loaded); null: runSimulation resolves it.
  std::shared_ptr<const pipeline::ResolvedController> resolved;
  TaskFile task;
  double duration_s = 0.0;        ///< <= 0: the task's duration_s
  bool realtime = false;          ///< pace the loop to the wall clock
  bool view = false;              ///< interactive window (needs a display)
  std::filesystem::path out_dir;  ///< empty: no files (log kept in memory only)
  bool snapshots = true;          ///< PNGs at start, end and every task.snapshot_every_ms
  int image_width = 640;
  int image_height = 480;
  bool plant_joint_dynamics = true;   ///< robot.yaml joint_dynamics in the plant
  double plant_friction_scale = 1.0;  ///< multiplies the plant's Coulomb friction
  /// The plant's effort reads as a joint-torque sensor on the link side (sim::PlantOptions).
  bool plant_link_side_torque = false;
  std::ostream* progress = nullptr;  ///< progress bar and warnings; nullptr: silent
  /// Cartesian controllers only: when set, the command source (e.g. a task::PathCommand or an
  /// experiment's stream) asked before every cycle, in place of the task's waypoints.
  task::CartesianSource* cartesian_source = nullptr;  ///< not owned; outlives the run
  /// Non-empty: every cycle, command and outcome recorded to this MCAP file, stamped with the
  /// simulated time (seconds since the start, as if the epoch).
  std::filesystem::path record_path;
  /// Set: a Foxglove live view (host/live_view.hpp) on this address, the run paced to the wall
  /// clock while a viewer is connected.
  std::optional<LiveViewOptions> foxglove;
  /// With `foxglove`: wait up to this long [s] for the first viewer before the first cycle.
  double foxglove_wait_s = 0.0;
};

/// What a recording wrote (SimSummary::recording).
struct RecordingSummary {
  std::filesystem::path path;
  std::uint64_t written = 0;  ///< messages in the file
  std::uint64_t dropped = 0;  ///< records a full lane refused
  std::uint64_t bytes = 0;
  double writer_cpu_s = 0.0;
  std::string error;  ///< the I/O error that stopped it ("" if none)
};

/// Every control cycle, as the controller saw and commanded it. Poses in the base frame.
struct SimLog {
  int dof = 0;
  bool cartesian = true;
  std::vector<double> time_s;
  std::vector<JointVector> position, velocity, torque;  ///< measured q, dq; commanded tau
  std::vector<JointVector> joint_reference;             ///< joint control: q reference
  std::vector<Eigen::Vector3d> tcp_position, reference_position;
  std::vector<Eigen::Quaterniond> tcp_orientation, reference_orientation;
  std::vector<Vector6d> contact_wrench;  ///< on the tool, base frame [N, N m]
  /// The controller's estimate of the same wrench (observer.enabled; empty when off): what a
  /// robot without the simulator's truth would see.
  std::vector<Vector6d> estimated_wrench;
  /// output.mode other than torque: the drives' position command (joint_pd's q_d, admittance's
  /// virtual arm), and in admittance the wrist sensor's wrench the virtual arm answered (the
  /// declared tool's weight and the tare off). Empty otherwise.
  std::vector<JointVector> position_command;
  std::vector<Vector6d> sensor_wrench;
  std::vector<double> cycle_cost_us;  ///< the controller's own time per cycle, plant excluded
  /// The energy tank's account after each cycle (passivity.* options).
  std::vector<pipeline::PassivitySnapshot> passivity;

  [[nodiscard]] std::size_t size() const noexcept { return time_s.size(); }
  /// |reference - measured| TCP position [m] and orientation angle [rad] at `row`.
  [[nodiscard]] double positionError(std::size_t row) const;
  [[nodiscard]] double orientationError(std::size_t row) const;
  /// Largest |q_ref - q| over joints [rad | m] at `row` (joint control).
  [[nodiscard]] double jointError(std::size_t row) const;
  /// The tank was on (passivity.enabled, fixed for a run): log.csv then has its columns. Known
  /// from the first row on.
  [[nodiscard]] bool passivityEnabled() const noexcept {
    return !passivity.empty() && passivity.front().enabled;
  }
  /// The momentum observer ran (observer.enabled): log.csv then has estimated_* columns.
  [[nodiscard]] bool estimateLogged() const noexcept { return !estimated_wrench.empty(); }
  /// The drives took positions (output.mode joint_pd, position, velocity): qcmd* columns.
  [[nodiscard]] bool commandLogged() const noexcept { return !position_command.empty(); }
  /// Admittance: sensor_* columns.
  [[nodiscard]] bool sensorLogged() const noexcept { return !sensor_wrench.empty(); }
};

struct SimSummary {
  std::string robot;
  std::string plugin;
  OutputMode output_mode = OutputMode::kTorque;  ///< what the drives took (output.mode)
  int dof = 0;
  bool cartesian = true;
  double simulated_s = 0.0;
  double wall_s = 0.0;
  double final_position_error_mm = 0.0;  ///< Cartesian: vs the final reference
  double final_orientation_error_deg = 0.0;
  double final_joint_error_rad = 0.0;  ///< joint control
  double max_torque_nm = 0.0;
  int max_torque_joint = 0;
  double max_torque_rate_nm_per_s = 0.0;
  /// Time from the last waypoint until the error stays within 1 mm / 0.5 deg (joint: 0.001 rad);
  /// NaN when it never settles.
  double settle_time_s = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t commands_sent = 0;
  std::uint64_t rejections = 0;
  std::uint64_t rate_limit_hits = 0;
  std::uint64_t effort_limit_hits = 0;
  std::uint64_t governor_hits = 0;        ///< cycles the motion governor acted in
  std::uint64_t wall_reference_hits = 0;  ///< cycles the walls moved the law's reference
  std::uint64_t wall_brake_hits = 0;      ///< cycles the walls' barrier braked the TCP
  std::uint64_t contact_speed_hits = 0;   ///< cycles the contact-speed stage acted in
  std::uint64_t faults = 0;
  /// Cycles whose controller time exceeded the control period: on a real arm each is a missed
  /// deadline (the simulation just waits).
  std::uint64_t overruns = 0;
  /// The control cycle's cost inside the simulation (CycleRecord::controller_s): the plant's
  /// step, logging and rendering excluded. Not a benchmark (unpinned, other work between cycles
  /// evicts caches); `comply bench` is.
  TimingSummary cycle_cost;
  /// The task's last command was refused: its target never came into force (the final errors
  /// above are against the last accepted reference). The run then failed.
  bool last_command_rejected = false;
  std::string last_rejection;
  /// Longest stretch with some joint's torque at its effort limit [s], and the joint. A law that
  /// pins a joint at its limit for long has lost control of it: the run then failed.
  double longest_saturation_s = 0.0;
  int saturated_joint = 0;
  std::string fault_reason;           ///< why the controller entered FAULT ("" if it did not)
  std::vector<std::string> messages;  ///< rejection reasons, warnings (first few)
  std::vector<std::filesystem::path> files;
  std::optional<RecordingSummary> recording;  ///< with SimRunOptions::record_path
};

/// Sustained saturation that fails a run [s] (libfranka's reflexes and polymetis's torque checks
/// stop a controller on the same sign of lost control).
inline constexpr double kMaxSaturationS = 0.5;

/// Exit code of a finished run: 1 on a fault, a refused final target or sustained saturation.
int simExitCode(const SimSummary& summary);

struct SimResult {
  SimSummary summary;
  SimLog log;
};

/// Runs the task. Throws std::runtime_error (or SimError, ModelError, PluginError) with a clear
/// message on bad input before the first cycle; a fault during the run is reported in the summary.
SimResult runSimulation(const SimRunOptions& options);

/// The tool contact force [N, base frame] averaged over the last `window` cycles at each row:
/// what a force sensor's filter reports. MuJoCo's rigid contacts (small solref) chatter at the
/// physics step, micrometres in amplitude, so a single cycle's force is on or off.
std::vector<Eigen::Vector3d> averagedContactForce(const SimLog& log, std::size_t window);

/// log.csv's header line and one row of it (one row per cycle; the run streams the file as it
/// goes, through sim_crash_guard.hpp). The tank's columns (tank_energy_j ... gain_fraction) come
/// last, and only when it was on, so the header needs the first row (SimLog::passivityEnabled).
void writeLogHeader(const SimLog& log, std::ostream& out);
void writeLogRow(const SimLog& log, std::size_t row, std::ostream& out);

/// Final errors and settle time (counted from `end_of_motion_s`) from the log.
void summarizeLog(const SimLog& log, double end_of_motion_s, SimSummary& summary);

/// Keeps `message` in the summary's notes (the first few) and shows it on `progress`.
void addMessage(SimSummary& summary, const std::string& message, std::ostream* progress);

/// Prints the summary for a human.
void printSummary(const SimSummary& summary, std::ostream& out);

}  // namespace comply::host
