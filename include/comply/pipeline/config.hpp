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
// The options, their defaults and their documentation are declared once, in option_table.hpp;
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
#include "comply/core/enum_names.hpp"
#include "comply/model/data.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/body_regions.hpp"
#include "comply/pipeline/contact_reflex.hpp"
#include "comply/pipeline/force_axes.hpp"
#include "comply/pipeline/momentum_observer.hpp"
#include "comply/pipeline/option_table.hpp"
#include "comply/pipeline/wall_geometry.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

enum class TimeoutBehavior { kHold, kReanchor };
inline constexpr EnumNames<TimeoutBehavior, 2> kTimeoutBehaviorNames{
    {{TimeoutBehavior::kHold, "hold"}, {TimeoutBehavior::kReanchor, "reanchor"}}};
enum class FrictionModel { kNone, kSigmoid, kViscousCoulomb };
inline constexpr EnumNames<FrictionModel, 3> kFrictionModelNames{
    {{FrictionModel::kNone, "none"},
     {FrictionModel::kSigmoid, "sigmoid"},
     {FrictionModel::kViscousCoulomb, "viscous_coulomb"}}};
/// How a torque beyond the effort limits is brought within them: each joint clipped on its own
/// (the direction of the law's torque turns), or the law's whole torque scaled (it keeps its
/// direction, and so does the wrench it commands).
enum class EffortSaturation { kClip, kScale };
inline constexpr EnumNames<EffortSaturation, 2> kEffortSaturationNames{
    {{EffortSaturation::kClip, "clip"}, {EffortSaturation::kScale, "scale"}}};

/// Joint friction compensation (compensation.friction.*; compensation.hpp has the formulas).
struct FrictionConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_FRICTION_OPTIONS)
};

/// Spring-dampers near the URDF limits (soft_limits.*).
struct SoftLimitConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_SOFT_LIMIT_OPTIONS)
};

/// What a command may ask against the measured arm and the host's clock (validation.*).
struct ValidationConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_VALIDATION_OPTIONS)
  double gain_tolerance = 1e-9;  ///< symmetry / PSD tolerance, relative; not an option
};

/// The payload held at the tip (compensation.payload.*); the model's model::Payload.
struct PayloadConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_PAYLOAD_OPTIONS)
};

/// Rate limits on the gains the law sees (gain_ramps.*): a step in a command becomes a ramp.
struct GainRampConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_GAIN_RAMP_OPTIONS)
};

/// The energy tank (passivity.*; gain_guard.hpp).
struct PassivityConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_PASSIVITY_OPTIONS)
};

/// The stability guard (stability_guard.*).
struct StabilityGuardConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_STABILITY_GUARD_OPTIONS)
};

/// The motion governor (governor.*; motion_governor.hpp).
struct GovernorConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_GOVERNOR_OPTIONS)
};

/// Virtual walls and boxes the TCP does not pass (walls:, boxes:, wall.*; virtual_walls.hpp).
struct WallConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_WALL_OPTIONS)
  std::vector<WallPlane> planes;  ///< walls: point and outward unit normal, base frame [m]
  std::vector<WallBox> boxes;     ///< boxes: min and max corners, base frame [m]
  [[nodiscard]] bool any() const noexcept { return !planes.empty() || !boxes.empty(); }
};

/// The TCP's speed bounded by what a contact may cost (contact_speed.*; contact_speed.hpp).
struct ContactSpeedConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_CONTACT_SPEED_OPTIONS)
};

/// The wrist force/torque sensor's reading as the cycle uses it (wrench_sensor.*).
struct WrenchSensorConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_WRENCH_SENSOR_OPTIONS)
};

/// Admittance (output.mode position or velocity; output.admittance.*).
struct AdmittanceConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_ADMITTANCE_OPTIONS)
};

/// What the cycle sends the drives (output.*; core/actuator_command.hpp).
struct OutputConfig {
  COMPLY_OPTION_MEMBERS(COMPLY_OUTPUT_OPTIONS)
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

  COMPLY_OPTION_MEMBERS(COMPLY_COMMAND_OPTIONS)
  ValidationConfig validation;

  COMPLY_OPTION_MEMBERS(COMPLY_COMPENSATION_OPTIONS)
  /// The robot adds gravity compensation itself (hardware::HardwareInterface::compensatesGravity;
  /// Franka, KUKA and UR do). Not read from a file: the host sets it from the hardware. Then the
  /// cycle adds no arm gravity, to the law's torque or to the FAULT hold; a payload still is.
  bool hardware_compensates_gravity = false;
  PayloadConfig payload;
  FrictionConfig friction;
  SoftLimitConfig soft_limits;

  // Per-joint lists hold one value (every joint) or one per joint until completeForRobot(), then
  // one per joint.
  COMPLY_OPTION_MEMBERS(COMPLY_SHAPING_OPTIONS)

  GainRampConfig gain_ramps;
  PassivityConfig passivity;
  StabilityGuardConfig stability_guard;
  GovernorConfig governor;           ///< governor.*: the speeds no command drives past
  WallConfig walls;                  ///< walls:, boxes:, wall.*: where the TCP does not go
  ReflexConfig reflex;               ///< reflex.*: what an unplanned contact trips
  ContactSpeedConfig contact_speed;  ///< contact_speed.*: what a contact may cost
  ObserverConfig observer;           ///< the external wrench estimate (observer.*)
  WrenchSensorConfig wrench_sensor;  ///< wrench_sensor.*
  ForceControlConfig force_control;  ///< force_control.*: force along task axes
  OutputConfig output;               ///< output.*

  /// Initial command (gains, task frame); the pose/joint reference is seeded on activation.
  /// Sized by completeForRobot().
  JointCommand initial_joint;
  CartesianCommand initial_cartesian;
};

/// Every option at its default (the option table's): what structs built from a configuration
/// start with before they are set from one.
const WrapperConfig& defaultConfig();

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
