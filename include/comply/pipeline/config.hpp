#pragma once
// Wrapper configuration, read from a YAML file shaped like a ros2_control controller file:
//
//   <controller_name>:
//     ros__parameters:
//       plugin: cartesian_impedance          # plugin name or .so path
//       robot: fr3                           # robot name or folder (robots/<name>)
//       ...                                  # every key below, with its default
//
// Every option has a default that is safe on a real arm; units are in the key or the comment.
// The options, their defaults and their documentation are declared once, in config_options.cpp;
// `comply config --defaults` prints them as the documented file (config/cartesian_impedance.yaml).
//
// Two steps, so that reading a file never touches another one:
//   parseWrapperText()   the file as written: types, ranges, unknown keys; no robot needed
//   completeForRobot()   robot defaults (joints, frames, friction), per-joint sizes, the initial
//                        commands for that many joints

#include <filesystem>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "comply/core/actuator_command.hpp"
#include "comply/core/commands.hpp"
#include "comply/model/data.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/force_axes.hpp"
#include "comply/pipeline/momentum_observer.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

enum class TimeoutBehavior { kHold, kReanchor };
enum class FrictionModel { kNone, kSigmoid, kViscousCoulomb };
/// How a torque beyond the effort limits is brought within them: each joint clipped on its own
/// (the direction of the law's torque turns), or the law's whole torque scaled (it keeps its
/// direction, and so does the wrench it commands).
enum class EffortSaturation { kClip, kScale };

struct FrictionConfig {
  FrictionModel model = FrictionModel::kNone;
  std::vector<double> phi1, phi2, phi3;  ///< sigmoid [N m], [s/rad], [rad/s]; default robot.yaml
  std::vector<double> viscous;           ///< N m s/rad
  std::vector<double> coulomb;           ///< N m
  double smoothing_velocity = 0.01;      ///< rad/s: tanh(dq / v) replaces sign(dq)
};

struct SoftLimitConfig {
  bool enabled = true;
  std::vector<double> margin;     ///< rad before the URDF limit where the spring starts
  std::vector<double> stiffness;  ///< N m/rad
  std::vector<double> damping;    ///< N m s/rad
};

struct ValidationConfig {
  double quaternion_tolerance = 1e-3;      ///< |norm - 1| renormalised below, rejected above
  double max_position_jump_m = 0.10;       ///< target vs measured TCP position
  double max_orientation_jump_rad = 0.60;  ///< target vs measured TCP orientation
  double max_joint_jump_rad = 0.50;        ///< joint target vs measured position
  double gain_tolerance = 1e-9;            ///< symmetry / PSD tolerance, relative
  double max_stamp_lead_s = 1.0;           ///< a command stamp ahead of the host's clock [s]
  /// The largest w_n T a gain may give on the arm's lightest inertia (gain_bound.hpp); 0: none.
  double max_wn_period = 0.35;
};

/// Rate limits on the gains the law sees (gain_ramps.*): a step in a command becomes a ramp. Each
/// rate bounds every entry of its matrix or vector per second; matrices move along the straight
/// line to the command, so they stay symmetric positive semi-definite.
struct GainRampConfig {
  bool enabled = false;
  double translational_stiffness_per_s = 10000.0;  ///< N/m per s
  double rotational_stiffness_per_s = 1000.0;      ///< N m/rad per s
  double joint_stiffness_per_s = 2000.0;           ///< N m/rad per s: joint law and nullspace
  double translational_damping_per_s = 1000.0;     ///< N s/m per s
  double rotational_damping_per_s = 100.0;         ///< N m s/rad per s
  double joint_damping_per_s = 200.0;              ///< N m s/rad per s: joint law and nullspace
  double damping_ratio_per_s = 5.0;                ///< 1/s
  double task_frame_rad_per_s = 1.0;               ///< angular rate of the task frame
};

/// The energy tank (passivity.*): it pays for the energy a stiffness or task-frame change injects
/// into the springs and refuses, smoothly, what it cannot pay (gain_guard.hpp).
struct PassivityConfig {
  bool enabled = false;
  double tank_initial_j = 1.0;            ///< T0 of the task account
  double tank_max_j = 2.0;                ///< ceiling: the damping refills it up to here
  double tank_min_j = 0.01;               ///< floor: never spent below
  double nullspace_tank_initial_j = 0.5;  ///< the nullspace's own account
  double nullspace_tank_max_j = 1.0;
};

/// The stability guard (stability_guard.*): what a running arm must never do, whatever the law
/// and the gains ask, each ending in FAULT with a named reason.
struct StabilityGuardConfig {
  bool enabled = true;
  double velocity_factor = 1.0;       ///< FAULT above this times a joint's URDF velocity limit
  double velocity_time_s = 0.005;     ///< ... for this long (a noisy sample is not a runaway)
  double position_margin_rad = 0.05;  ///< FAULT this far past a URDF position limit [rad | m]
  double saturation_time_s = 1.0;  ///< FAULT when a joint sits at its effort limit this long; 0 off
  /// The energy rule (energy_watch.hpp): FAULT on an oscillation whose energy grows `energy_growth`
  /// times over windows of energy_window_s, each higher than the last, while the command holds
  /// still. 0: off.
  double energy_window_s = 0.25;
  double energy_growth = 4.0;    ///< [-] over a run of growing windows
  double energy_floor_j = 0.05;  ///< [J] the energy must exceed this (weighted by joint inertia)
};

/// The wrist force/torque sensor's reading as the cycle uses it (wrench_sensor.*;
/// cycle_wrench.cpp).
struct WrenchSensorConfig {
  /// First-order low-pass on the reading (the tool's weight off, before the tare) [Hz]; 0: off.
  double filter_hz = 0.0;
};

/// Admittance (output.mode position or velocity): the law's torque, with the measured external
/// wrench, drives a virtual arm (the arm's own inertia plus what is added here, without gravity
/// or friction) whose motion the arm's position or velocity drives follow.
struct AdmittanceConfig {
  /// Mass added at the TCP along the task frame's x, y, z [kg]: a heavier, slower virtual arm.
  Eigen::Vector3d added_mass_kg = Eigen::Vector3d::Zero();
  /// Rotational inertia added at the TCP about the task frame's axes [kg m^2].
  Eigen::Vector3d added_inertia_kg_m2 = Eigen::Vector3d::Zero();
  double velocity_factor = 0.5;  ///< joint speed bound: this times the URDF velocity limit
  /// Joint acceleration bound [rad/s^2 | m/s^2]: a net for a wild sensor reading, to be kept
  /// well above what the law asks (a bound in the loop makes the virtual arm overshoot).
  double max_acceleration_rad_per_s2 = 100.0;
  /// The virtual arm is kept within this of the measured one per joint [rad | m]: what a blocked
  /// or lagging arm can wind up.
  double max_tracking_error_rad = 0.05;
  /// velocity mode: the command is the virtual velocity plus this times (q_virtual - q) [1/s], so
  /// the drives' own integration error does not accumulate.
  double velocity_correction_per_s = 10.0;
};

/// What the cycle sends the drives (output.*; core/actuator_command.hpp).
struct OutputConfig {
  OutputMode mode = OutputMode::kTorque;
  AdmittanceConfig admittance;
};

struct WrapperConfig {
  std::string name;    ///< controller name (top-level YAML key)
  std::string source;  ///< where it was read from (file name), for messages
  std::string plugin;
  plugin::ParameterMap plugin_parameters;
  std::string robot;                ///< name or folder
  std::vector<std::string> joints;  ///< default: robot.yaml joints
  std::string base_frame;           ///< default: robot.yaml base_frame
  std::string tip_frame;            ///< default: robot.yaml tcp_frame
  int dof = 0;                      ///< number of joints; 0 until completeForRobot()
  /// The robot the configuration was completed for (completeForRobot()); read once, reused by
  /// resolveController().
  std::shared_ptr<const model::RobotDescription> robot_description;
  /// The `initial:` block as written; completeForRobot() turns it into the initial commands.
  std::shared_ptr<const nlohmann::json> initial_block;

  double command_timeout_s = 0.5;
  /// A new timed chunk takes over from the reference in force over this time [s] (0: at once).
  double chunk_blend_time_s = 0.1;
  TimeoutBehavior timeout_behavior = TimeoutBehavior::kHold;
  ValidationConfig validation;

  bool gravity_compensation = true;
  /// The robot adds gravity compensation itself (hardware::HardwareInterface::compensatesGravity;
  /// Franka, KUKA and UR do). Not read from a file: the host sets it from the hardware. Then the
  /// cycle adds no arm gravity, to the law's torque or to the FAULT hold; a payload still is.
  bool hardware_compensates_gravity = false;
  bool payload_compensation = false;
  model::Payload payload;
  FrictionConfig friction;
  SoftLimitConfig soft_limits;

  // Per-joint lists hold one value (every joint) or one per joint until completeForRobot(), then
  // one per joint.
  double filter_alpha = 1.0;              ///< tau_f = alpha tau + (1 - alpha) tau_f,prev; 1 = off
  std::vector<double> torque_rate_limit;  ///< N m/s per joint
  std::vector<double> effort_limit;       ///< N m; empty: URDF <limit effort>
  EffortSaturation effort_saturation = EffortSaturation::kClip;
  std::vector<double> fault_damping;  ///< N m s/rad of the safe holding torque
  /// A joint state unchanged bit for bit this long while the torque changes is a stale sensor
  /// stream (FAULT); 0: never.
  double frozen_state_timeout_s = 0.1;

  GainRampConfig gain_ramps;
  PassivityConfig passivity;
  StabilityGuardConfig stability_guard;
  ObserverConfig observer;           ///< the external wrench estimate (observer.*)
  WrenchSensorConfig wrench_sensor;  ///< wrench_sensor.*
  ForceControlConfig force_control;  ///< force_control.*: force along task axes
  OutputConfig output;               ///< output.*

  /// Initial command (gains, task frame); the pose/joint reference is seeded on activation.
  /// Sized by completeForRobot().
  JointCommand initial_joint;
  CartesianCommand initial_cartesian;
};

/// Reads `controller_name` (or the only controller in the file when empty) from YAML text
/// (`source` names it in messages). Touches no file. Throws InputError naming the source and the
/// key on any error.
WrapperConfig parseWrapperText(const std::string& yaml_text, const std::string& source,
                               const std::string& controller_name = {});

/// Completes `config` for `robot`: joints and frames default to the robot's, per-joint lists are
/// expanded (one value) or checked (one per joint), sigmoid friction defaults to robot.yaml, and
/// the initial commands are read for that many joints. Throws InputError naming the key.
void completeForRobot(WrapperConfig& config, std::shared_ptr<const model::RobotDescription> robot);

/// The documented controller file with every option at its default, for `plugin` on `robot`
/// (`comply config --defaults`). `cartesian` selects the initial gains that are listed.
std::string documentedDefaults(const std::string& controller_name, const std::string& plugin,
                               const std::string& robot, const std::string& tip_frame,
                               bool cartesian);

/// parseWrapperText() + completeForRobot() with the robot the file names (loaded once).
WrapperConfig parseWrapperConfig(const std::string& yaml_text, const std::string& source,
                                 const std::string& controller_name = {});

/// The same from a file.
WrapperConfig loadWrapperConfig(const std::filesystem::path& file,
                                const std::string& controller_name = {});

}  // namespace comply::pipeline
