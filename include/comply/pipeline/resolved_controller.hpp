#pragma once
// A controller resolved once, before any cycle: the robot description, its model, the plugin
// library and the kind of command it takes, and every configuration number compiled into the
// fixed-size form the cycle reads. The simulator, the benchmarks, `comply validate` and every
// live host build one and share it; nothing is looked up, parsed or loaded again later.
//
//   auto resolved = resolveController(loadWrapperConfig("controller.yaml"));
//   CartesianWrapper wrapper(resolved);   // or JointWrapper, per resolved->cartesian()

#include <memory>
#include <string>
#include <vector>

#include "comply/core/capacity.hpp"
#include "comply/core/commands.hpp"
#include "comply/model/data.hpp"
#include "comply/model/model.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/gain_bound.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

/// Friction compensation with one entry per joint (see compensation.hpp for the formulas).
struct FrictionParameters {
  FrictionModel model = defaultConfig().friction.model;
  JointVector phi1, phi2, phi3;  ///< sigmoid [N m], [s/rad], [rad/s]
  JointVector viscous, coulomb;  ///< [N m s/rad], [N m]
  double smoothing_velocity = defaultConfig().friction.smoothing_velocity;  ///< [rad/s]
};

/// Soft joint limits with one entry per joint, the URDF limits included.
struct SoftLimitParameters {
  bool enabled = defaultConfig().soft_limits.enabled;
  JointVector lower, upper;  ///< URDF position limits [rad | m]
  JointVector margin;        ///< [rad | m] inside each limit where the spring starts
  JointVector stiffness;     ///< [N m/rad]
  JointVector damping;       ///< [N m s/rad]
};

/// The walls and boxes as the cycle reads them (virtual_walls.hpp): inline, no heap.
struct WallParameters {
  WallSet set;  ///< empty: the stage is off
  BarrierGains gains;
};

/// The contact-speed stage's numbers (contact_speed.hpp), compiled from contact_speed.*, the body
/// region's row (body_regions.hpp) and the payload.
struct ContactSpeedParameters {
  bool enabled = false;
  double force_limit_n = 0.0;      ///< what a contact may reach
  double stiffness_n_per_m = 0.0;  ///< of what the TCP meets
  double body_mass_kg = 0.0;       ///< the region's, in a reduced mass; 0: clamped (the default)
  double payload_mass_kg = 0.0;    ///< compensation.payload.mass_kg, a point mass at the TCP
};

/// Everything the cycle reads, each per-joint value sized to the controller's dof. Every member
/// is set by resolveController() from the configuration; until then, the option table's defaults.
struct CycleParameters {
  COMPLY_OPTION_MEMBERS(COMPLY_COMMAND_OPTIONS)
  COMPLY_OPTION_MEMBERS(COMPLY_COMPENSATION_OPTIONS)
  bool hardware_compensates_gravity = false;  ///< see WrapperConfig
  model::Payload payload;
  FrictionParameters friction;
  SoftLimitParameters soft_limits;
  double filter_alpha = defaultConfig().filter_alpha;
  JointVector torque_rate_limit;  ///< [N m/s]
  JointVector effort_limit;       ///< [N m]
  EffortSaturation effort_saturation = defaultConfig().effort_saturation;
  JointVector fault_damping;  ///< [N m s/rad]
  double frozen_state_timeout_s = defaultConfig().frozen_state_timeout_s;
  GainRampConfig gain_ramps;
  PassivityConfig passivity;
  StabilityGuardConfig stability_guard;
  GovernorConfig governor;
  WallParameters walls;
  ReflexConfig reflex;
  ContactSpeedParameters contact_speed;
  ObserverConfig observer;
  OutputConfig output;
  WrenchSensorConfig wrench_sensor;
  ForceControlConfig force_control;
  /// compensation.payload.enabled as written: the declared payload is the tool beyond the wrist
  /// sensor, whose weight comes off the sensor's reading in every mode (wrist_sensor.hpp) and whose
  /// inertial force comes off it in admittance (virtual_arm.hpp). payload_compensation
  /// (its weight in the torque) is off in admittance, this is not.
  bool payload_on_sensor = false;
  JointVector velocity_limit;  ///< URDF [rad/s | m/s], for the stability guard and admittance
  /// governor.velocity_fraction x velocity_limit: what the governor keeps each joint below and
  /// what a joint chunk may ask [rad/s | m/s]; 0 where the URDF gives no limit.
  JointVector governed_speed;
  /// Each joint's lightest inertia [kg m^2 | kg] over the workspace (the declared rotor inertias
  /// included; gain_bound.hpp): the energy rule's weights, the governor's and the controlled
  /// stop's bound on a joint's damping.
  JointVector joint_inertia;
  double tcp_mass_kg = 0.0;        ///< the lightest apparent mass at the TCP (the same way)
  double tcp_inertia_kg_m2 = 0.0;  ///< the lightest apparent rotational inertia at the TCP
};

struct ResolvedController {
  WrapperConfig config;  ///< as read (names, plugin parameters, initial command)
  model::RobotDescription robot;
  std::shared_ptr<const model::Model> model;  ///< immutable: one serves many controllers
  std::shared_ptr<const plugin::PluginLibrary> plugin;
  int command_kind = 0;  ///< COMPLY_COMMAND_JOINT or COMPLY_COMMAND_CARTESIAN (the plugin's)
  int dof = 0;
  CycleParameters parameters;
  /// The gains the arm renders stably (gain_bound.hpp): the intake refuses commands above them.
  GainBound gain_bound;
  /// What the controller takes but its user should know (a robot without rotor inertias): the
  /// hosts print each once, before the first cycle.
  std::vector<std::string> warnings;

  [[nodiscard]] bool cartesian() const noexcept;
};

/// Loads the robot, builds the model, opens the plugin and compiles the parameters. Throws
/// model::ModelError, plugin::PluginError or InputError naming the option at fault.
std::shared_ptr<const ResolvedController> resolveController(const WrapperConfig& config);

/// Friction parameters sized to `dof` from a configuration.
FrictionParameters compileFriction(const FrictionConfig& friction, int dof);
/// Soft-limit parameters from a configuration and the URDF limits.
SoftLimitParameters compileSoftLimits(const SoftLimitConfig& soft_limits, const JointVector& lower,
                                      const JointVector& upper);

}  // namespace comply::pipeline
