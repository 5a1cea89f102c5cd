#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {
namespace {

JointVector toJointVector(const std::vector<double>& values, int dof, double fallback = 0.0) {
  JointVector result = JointVector::Constant(dof, fallback);
  for (int i = 0; i < dof && i < static_cast<int>(values.size()); ++i) {
    result[i] = values[static_cast<std::size_t>(i)];
  }
  return result;
}

JointVector effortLimits(const WrapperConfig& config, const model::Model& model) {
  JointVector limit(config.dof);
  for (int i = 0; i < config.dof; ++i) {
    limit[i] = config.effort_limit.empty() ? model.limits(i).effort
                                           : config.effort_limit[static_cast<std::size_t>(i)];
    if (!(limit[i] > 0.0)) {
      throw InputError(InputErrc::kInconsistent, config.name, "effort_limit_nm",
                       "joint '" + config.joints[static_cast<std::size_t>(i)] +
                           "' has no effort limit in the URDF; set effort_limit_nm");
    }
  }
  return limit;
}

}  // namespace

bool ResolvedController::cartesian() const noexcept {
  return command_kind == COMPLY_COMMAND_CARTESIAN;
}

FrictionParameters compileFriction(const FrictionConfig& friction, int dof) {
  FrictionParameters compiled;
  compiled.model = friction.model;
  compiled.phi1 = toJointVector(friction.phi1, dof);
  compiled.phi2 = toJointVector(friction.phi2, dof);
  compiled.phi3 = toJointVector(friction.phi3, dof);
  compiled.viscous = toJointVector(friction.viscous, dof);
  compiled.coulomb = toJointVector(friction.coulomb, dof);
  compiled.smoothing_velocity = friction.smoothing_velocity;
  return compiled;
}

SoftLimitParameters compileSoftLimits(const SoftLimitConfig& soft_limits, const JointVector& lower,
                                      const JointVector& upper) {
  const auto dof = static_cast<int>(lower.size());
  SoftLimitParameters compiled;
  compiled.enabled = soft_limits.enabled;
  compiled.lower = lower;
  compiled.upper = upper;
  compiled.margin = toJointVector(soft_limits.margin, dof);
  compiled.stiffness = toJointVector(soft_limits.stiffness, dof);
  compiled.damping = toJointVector(soft_limits.damping, dof);
  return compiled;
}

/// The rotor inertias the robot declares, in the order of `joints` (empty when it declares none):
/// what a drive's torque accelerates besides the links.
std::vector<double> declaredArmature(const model::RobotDescription& robot,
                                     const std::vector<std::string>& joints) {
  if (!robot.joint_dynamics || robot.joint_dynamics->armature.size() != robot.joints.size()) {
    return {};
  }
  std::vector<double> armature(joints.size(), 0.0);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const auto it = std::find(robot.joints.begin(), robot.joints.end(), joints[i]);
    if (it != robot.joints.end()) {
      armature[i] = robot.joint_dynamics->armature[it - robot.joints.begin()];
    }
  }
  return armature;
}

namespace {

/// The robot declares a rotor inertia above zero on some joint.
bool hasArmature(const ResolvedController& resolved) {
  const std::vector<double> armature = declaredArmature(resolved.robot, resolved.robot.joints);
  return std::any_of(armature.begin(), armature.end(), [](double value) { return value > 0.0; });
}

/// The contact-speed stage's numbers (contact_speed.hpp): the body region's row unless the file
/// gives its own, and the payload. The rotors are in the laws' M(q) (loadModelAndPlugin), whose
/// mass the stage reads; the admittance modes, whose model has none, it refuses.
ContactSpeedParameters compileContactSpeed(const WrapperConfig& config) {
  const ContactSpeedConfig& contact = config.contact_speed;
  const BodyRegionLimits region = bodyRegionLimits(contact.body_region);
  ContactSpeedParameters compiled;
  compiled.enabled = contact.enabled;
  compiled.force_limit_n =
      contact.force_limit_n > 0.0 ? contact.force_limit_n : forceLimit(region, contact.contact);
  compiled.stiffness_n_per_m =
      contact.stiffness_n_per_m > 0.0 ? contact.stiffness_n_per_m : region.stiffness_n_per_m;
  compiled.body_mass_kg = contact.body_mass ? region.effective_mass_kg : 0.0;
  compiled.payload_mass_kg = config.payload.mass_kg;
  return compiled;
}

/// Step 1: the robot's description (loaded unless the configuration carries one), its model with
/// the configuration's joints and frames, and the plugin, whose command kind decides the rest.
void loadModelAndPlugin(ResolvedController& resolved) {
  WrapperConfig& config = resolved.config;
  if (!config.robot_description) {
    completeForRobot(config, std::make_shared<const model::RobotDescription>(
                                 model::loadRobotDescription(config.robot)));
  }
  resolved.robot = *config.robot_description;
  model::ModelOptions options = resolved.robot.modelOptions(config.tip_frame);
  options.joint_names = config.joints;
  options.base_frame = config.base_frame;
  // The laws' M(q) is the arm's, rotors included, so a damping ratio is one on the arm it damps.
  // An admittance law drives a virtual arm of bare links (virtual_arm.hpp), whose M it reads.
  if (!isAdmittance(config.output.mode)) {
    options.armature = declaredArmature(resolved.robot, config.joints);
  }
  resolved.model = std::make_shared<const model::Model>(resolved.robot.loadModel(options));
  resolved.dof = resolved.model->dof();
  if (resolved.dof != config.dof) {
    throw std::runtime_error(config.name + ": the model has " + std::to_string(resolved.dof) +
                             " joints but the configuration lists " + std::to_string(config.dof));
  }
  resolved.plugin = std::make_shared<const plugin::PluginLibrary>(config.plugin);
  resolved.command_kind = resolved.plugin->api().command_kind;
}

/// Step 2: every number the cycle reads, as fixed-size vectors.
void compileParameters(ResolvedController& resolved) {
  const WrapperConfig& config = resolved.config;
  const model::Model& model = *resolved.model;
  const int dof = resolved.dof;
  JointVector lower(dof);
  JointVector upper(dof);
  for (int i = 0; i < dof; ++i) {
    lower[i] = model.limits(i).lower;
    upper[i] = model.limits(i).upper;
  }
  CycleParameters& parameters = resolved.parameters;
  COMPLY_OPTION_COPY(COMPLY_COMMAND_OPTIONS, parameters, config)
  COMPLY_OPTION_COPY(COMPLY_COMPENSATION_OPTIONS, parameters, config)
  parameters.hardware_compensates_gravity = config.hardware_compensates_gravity;
  parameters.payload = model::Payload{config.payload.mass_kg, config.payload.com_in_tip};
  parameters.friction = compileFriction(config.friction, dof);
  parameters.soft_limits = compileSoftLimits(config.soft_limits, lower, upper);
  parameters.filter_alpha = config.filter_alpha;
  parameters.torque_rate_limit = toJointVector(config.torque_rate_limit, dof);
  parameters.effort_limit = effortLimits(config, model);
  parameters.effort_saturation = config.effort_saturation;
  parameters.gain_ramps = config.gain_ramps;
  parameters.passivity = config.passivity;
  parameters.stability_guard = config.stability_guard;
  parameters.governor = config.governor;
  (void)compileWalls(config.walls.planes, config.walls.boxes, parameters.walls.set);  // parse: fits
  parameters.walls.gains =
      BarrierGains{config.walls.brake_distance_m, config.walls.stiffness_n_per_m,
                   config.walls.damping_n_s_per_m};
  parameters.reflex = config.reflex;
  parameters.contact_speed = compileContactSpeed(config);
  parameters.observer = config.observer;
  parameters.velocity_limit.resize(dof);
  for (int i = 0; i < dof; ++i) {
    parameters.velocity_limit[i] = model.limits(i).velocity;
  }
  parameters.governed_speed = config.governor.velocity_fraction * parameters.velocity_limit;
  parameters.fault_damping = toJointVector(config.fault_damping, dof);
  parameters.frozen_state_timeout_s = config.frozen_state_timeout_s;
  parameters.output = config.output;
  parameters.payload_on_sensor = config.payload_compensation;
  parameters.wrench_sensor = config.wrench_sensor;
  parameters.force_control = config.force_control;
}

/// Step 3: an admittance law drives a virtual arm (virtual_arm.hpp): it has no weight or friction
/// to carry (the arm's own position control carries them), and a torque-rate limit on it would
/// only delay the virtual arm's answer to a contact. Its state is computed, not measured, so it
/// cannot go stale; the arm's own drives watch their encoders. The momentum observer would
/// estimate the virtual arm's wrench; the contact wrench of an admittance arm is its force/torque
/// sensor's.
void adaptToOutputMode(ResolvedController& resolved) {
  if (!isAdmittance(resolved.config.output.mode)) {
    return;
  }
  CycleParameters& parameters = resolved.parameters;
  parameters.gravity_compensation = false;
  parameters.payload_compensation = false;
  parameters.friction.model = FrictionModel::kNone;
  parameters.torque_rate_limit.setConstant(resolved.dof, std::numeric_limits<double>::infinity());
  parameters.frozen_state_timeout_s = 0.0;
  parameters.observer.enabled = false;
}

/// The arm's lightest inertias, its rotors included: the model's M carries them, except in the
/// admittance modes, whose model is the virtual arm's bare links (loadModelAndPlugin).
GainBound armInertias(const ResolvedController& resolved) {
  const model::Model& model = *resolved.model;
  const std::vector<double> extra = model.armature().empty()
                                        ? declaredArmature(resolved.robot, model.jointNames())
                                        : std::vector<double>{};
  return lightestInertias(model, toJointVector(extra, extra.empty() ? 0 : resolved.dof));
}

/// The gain bound of the output mode (gain_bound.hpp): the arm's inertias with its rotor inertias
/// (torque, with the torque-rate limit; joint_pd, whose drives' own gains are checked too with a
/// Cartesian law), or the admittance modes' virtual arm. Where the inertias are bare links' (the
/// virtual arm; a robot that declares no rotor inertias) only translation is bounded: a geared
/// wrist's bare links are a few hundredths of its rotors (the FR3's lightest rotational inertia
/// at the TCP 1.0e-4 kg m^2, against 0.040 with its rotors), and a bound on them would refuse
/// every robot's default rotational stiffness.
GainBound modeBound(const ResolvedController& resolved, const GainBound& arm) {
  const WrapperConfig& config = resolved.config;
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  GainBound bound = arm;
  bound.robot = resolved.robot.name;
  if (isAdmittance(config.output.mode)) {
    const AdmittanceConfig& admittance = config.output.admittance;
    bound = lightestInertias(
        *resolved.model, {}, 2000,
        {admittance.added_mass_kg.minCoeff(), admittance.added_inertia_kg_m2.minCoeff()});
    bound.robot = resolved.robot.name + " virtual arm";
  } else if (config.output.mode == OutputMode::kTorque) {
    bound.torque_rate_limit = resolved.parameters.torque_rate_limit;
    bound.rate_limit_swing_nm = config.validation.rate_limit_swing_nm;
  } else {
    bound.drive_gains = config.output.mode == OutputMode::kJointPd && resolved.cartesian();
  }
  bound.bare_links = isAdmittance(config.output.mode) || !hasArmature(resolved);
  if (bound.bare_links && bound.enabled()) {
    bound.rotational_inertia_kg_m2 = kUnbounded;
    bound.joint_inertia.setConstant(resolved.dof, kUnbounded);
  }
  bound.max_wn_period = config.validation.max_wn_period;
  return bound;
}

/// Step 4: the robot-dependent gain bound of the output mode, which the initial command must
/// keep, and the joint inertias the stability guard's energy rule weighs speeds with.
void boundGains(ResolvedController& resolved) {
  const WrapperConfig& config = resolved.config;
  const GainBound arm = armInertias(resolved);
  if (config.validation.max_wn_period > 0.0) {
    resolved.gain_bound = modeBound(resolved, arm);
    // The initial command is checked at 1 kHz: the period is the host's, known at the first cycle.
    const Verdict verdict =
        resolved.cartesian() ? checkRenderable(config.initial_cartesian, resolved.gain_bound, 1e-3)
                             : checkRenderable(config.initial_joint, resolved.gain_bound, 1e-3);
    if (!verdict.accepted) {
      const bool by_rate = verdict.message.find("torque-rate limit") != std::string::npos;
      throw InputError(InputErrc::kOutOfRange, config.name, "initial",
                       verdict.message + " at 1 kHz (output.mode " +
                           std::string(toString(config.output.mode)) + "); lower it, or set " +
                           (by_rate ? "torque_rate_limit_nm_per_s or validation.rate_limit_swing_nm"
                                    : "validation.max_wn_period"));
    }
    if (!isAdmittance(config.output.mode) && !hasArmature(resolved)) {
      resolved.warnings.push_back(
          resolved.robot.name +
          " declares no rotor inertias (robot.yaml joint_dynamics.armature): the laws' M(q) and "
          "the gain bound take its bare links, and only translational gains are bounded "
          "(validation.max_wn_period); rotational, joint and nullspace gains are not");
    }
  }
  // The lightest joint inertias (the arm's, rotor inertias included) weigh the energy rule and
  // bound the governor's and the stop's damping (deadbeat on the lightest inertia is stable on
  // every heavier one).
  resolved.parameters.joint_inertia = arm.joint_inertia;
  resolved.parameters.tcp_mass_kg = arm.translational_mass_kg;
  resolved.parameters.tcp_inertia_kg_m2 = arm.rotational_inertia_kg_m2;
}

/// Step 5: choices that cannot hold together.
void checkConsistency(const ResolvedController& resolved) {
  const WrapperConfig& config = resolved.config;
  const CycleParameters& parameters = resolved.parameters;
  if (parameters.force_control.source == ForceSource::kObserver && !parameters.observer.enabled) {
    throw InputError(InputErrc::kInconsistent, config.name, "force_control.source",
                     isAdmittance(config.output.mode)
                         ? "observer, but admittance (output.mode " +
                               std::string(toString(config.output.mode)) +
                               ") runs no observer; use sensor"
                         : "observer, but observer.enabled is false");
  }
  // The governor keeps joints below the speed the guard faults at; at or above it, the guard
  // would fault on motion the governor allows.
  const GovernorConfig& governor = parameters.governor;
  const StabilityGuardConfig& guard = parameters.stability_guard;
  if (governor.enabled && guard.enabled && governor.velocity_fraction >= guard.velocity_factor) {
    throw InputError(InputErrc::kInconsistent, config.name, "governor.velocity_fraction",
                     std::to_string(governor.velocity_fraction) +
                         " is not below stability_guard.velocity_factor (" +
                         std::to_string(guard.velocity_factor) + ")");
  }
  // The contact speed bounds the TCP's speed through the arm's own inertia: there is no TCP for
  // a joint law, and position or velocity drives meet a contact with their servo's stiffness.
  if (config.contact_speed.enabled && !resolved.cartesian()) {
    throw InputError(
        InputErrc::kInconsistent, config.name, "contact_speed.enabled",
        "needs a Cartesian law (the plugin " + config.plugin + " takes joint commands)");
  }
  if (config.contact_speed.enabled && isAdmittance(config.output.mode)) {
    throw InputError(InputErrc::kInconsistent, config.name, "contact_speed.enabled",
                     "not with output.mode " + std::string(toString(config.output.mode)) +
                         ": its drives push through a contact with their servo, not with the "
                         "arm's inertia; bound the TCP with governor.tcp_speed_m_per_s");
  }
  // Walls bound the TCP's reference, which only a Cartesian law has.
  if (config.walls.any() && !resolved.cartesian()) {
    throw InputError(
        InputErrc::kInconsistent, config.name, "walls",
        "need a Cartesian law (the plugin " + config.plugin + " takes joint commands)");
  }
  // The barrier's damper acts on the TCP's apparent mass one cycle late: past half of deadbeat on
  // the lightest of it (at 1 kHz, as the initial command is checked) it would ring, not brake.
  // Any Cartesian law: a command may set a box at run time.
  const double damping_bound = parameters.tcp_mass_kg / (2.0 * 1e-3);
  if (resolved.cartesian() && parameters.tcp_mass_kg > 0.0 &&
      config.walls.damping_n_s_per_m > damping_bound) {
    throw InputError(InputErrc::kOutOfRange, config.name, "wall.damping_n_s_per_m",
                     std::to_string(config.walls.damping_n_s_per_m) +
                         " exceeds half of deadbeat on the TCP's lightest apparent mass (" +
                         std::to_string(parameters.tcp_mass_kg) + " kg) at 1 kHz: at most " +
                         std::to_string(damping_bound));
  }
  // A retreat moves the TCP's reference; a joint law holds instead (hold or fault).
  if (config.reflex.enabled && config.reflex.reaction == ReflexReaction::kRetreat &&
      !resolved.cartesian()) {
    throw InputError(InputErrc::kInconsistent, config.name, "reflex.reaction",
                     "retreat needs a Cartesian law (the plugin " + config.plugin +
                         " takes joint commands); use hold or fault");
  }
}

}  // namespace

std::shared_ptr<const ResolvedController> resolveController(const WrapperConfig& input) {
  auto resolved = std::make_shared<ResolvedController>();
  resolved->config = input;
  loadModelAndPlugin(*resolved);
  compileParameters(*resolved);
  adaptToOutputMode(*resolved);
  boundGains(*resolved);
  checkConsistency(*resolved);
  return resolved;
}

}  // namespace comply::pipeline
