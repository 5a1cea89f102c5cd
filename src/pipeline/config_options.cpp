#include "config_options.hpp"

#include <limits>

namespace comply::pipeline::options {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Option number(const char* key, const char* default_text, const char* comment, double min,
              double max, bool min_exclusive, std::function<void(WrapperConfig&, double)> set) {
  Option option{key, Kind::kNumber, default_text, comment, min, max, min_exclusive};
  option.apply = [set = std::move(set)](WrapperConfig& config, const Value& value) {
    set(config, value.number);
  };
  return option;
}

Option flag(const char* key, const char* default_text, const char* comment,
            std::function<void(WrapperConfig&, bool)> set) {
  Option option{key, Kind::kFlag, default_text, comment};
  option.apply = [set = std::move(set)](WrapperConfig& config, const Value& value) {
    set(config, value.flag);
  };
  return option;
}

Option perJoint(const char* key, const char* default_text, const char* comment, double min,
                bool min_exclusive, std::vector<double> WrapperConfig::*list) {
  Option option{key, Kind::kPerJoint, default_text, comment, min, kInfinity, min_exclusive};
  option.apply = [list](WrapperConfig& config, const Value& value) {
    config.*list = value.numbers;
  };
  return option;
}

Option perJointIn(const char* key, const char* default_text, const char* comment,
                  std::function<std::vector<double>&(WrapperConfig&)> list, double min = 0.0) {
  Option option{key, Kind::kPerJoint, default_text, comment, min, kInfinity};
  option.apply = [list = std::move(list)](WrapperConfig& config, const Value& value) {
    list(config) = value.numbers;
  };
  return option;
}

/// Three numbers into the vector `member` returns; zero by default.
Option vector3(const char* key, const char* comment, double min, double max,
               std::function<Eigen::Vector3d&(WrapperConfig&)> member) {
  Option option{key, Kind::kVector3, "[0.0, 0.0, 0.0]", comment, min, max};
  option.apply = [member = std::move(member)](WrapperConfig& config, const Value& value) {
    member(config) = Eigen::Vector3d(value.numbers[0], value.numbers[1], value.numbers[2]);
  };
  return option;
}

Option spaced(Option option) {
  option.blank_line_before = true;
  return option;
}

// What the wrapper accepts from a command source and when it stops waiting for one.
void addCommandOptions(std::vector<Option>& table) {
  table.push_back(spaced(
      number("command_timeout_s", "0.5", "no command for this long -> timeout_behavior; 0: never",
             0.0, kInfinity, false, [](WrapperConfig& c, double v) { c.command_timeout_s = v; })));
  Option behavior{"timeout_behavior", Kind::kChoice, "hold",
                  "hold: keep the last pose, stop its motion; reanchor: measured pose"};
  behavior.choices = "hold|reanchor";
  behavior.apply = [](WrapperConfig& c, const Value& v) {
    c.timeout_behavior = v.text == "hold" ? TimeoutBehavior::kHold : TimeoutBehavior::kReanchor;
  };
  table.push_back(behavior);
  table.push_back(number("chunk_blend_time_s", "0.1",
                         "s over which a new timed chunk takes over from the reference in force",
                         0.0, 10.0, false,
                         [](WrapperConfig& c, double v) { c.chunk_blend_time_s = v; }));
  table.push_back(number(
      "validation.quaternion_tolerance", "1.0e-3", "|norm - 1| renormalised below, rejected above",
      0.0, 0.5, true, [](WrapperConfig& c, double v) { c.validation.quaternion_tolerance = v; }));
  table.push_back(number("validation.max_position_jump_m", "0.10",
                         "target vs measured TCP position", 0.0, kInfinity, true,
                         [](WrapperConfig& c, double v) { c.validation.max_position_jump_m = v; }));
  table.push_back(number(
      "validation.max_orientation_jump_rad", "0.60", "target vs measured TCP orientation", 0.0,
      M_PI, true, [](WrapperConfig& c, double v) { c.validation.max_orientation_jump_rad = v; }));
  table.push_back(number("validation.max_joint_jump_rad", "0.50",
                         "joint target vs measured position (joint commands)", 0.0, kInfinity, true,
                         [](WrapperConfig& c, double v) { c.validation.max_joint_jump_rad = v; }));
  table.push_back(number(
      "validation.max_wn_period", "0.35",
      "largest w_n T a stiffness or damping may give on the arm's lightest inertia (0: no bound)",
      0.0, 0.43, false, [](WrapperConfig& c, double v) { c.validation.max_wn_period = v; }));
  table.push_back(number("validation.max_stamp_lead_s", "1.0",
                         "s a command's stamp may be ahead of the host's clock (clock skew)", 0.0,
                         kInfinity, true,
                         [](WrapperConfig& c, double v) { c.validation.max_stamp_lead_s = v; }));
}

// Model-based torques added to the control law: gravity, a held payload, joint friction.
void addCompensationOptions(std::vector<Option>& table) {
  table.push_back(spaced(flag("compensation.gravity", "true", "g(q) from the URDF",
                              [](WrapperConfig& c, bool v) { c.gravity_compensation = v; })));
  table.push_back(flag("compensation.payload.enabled", "false", "a load held at the tip",
                       [](WrapperConfig& c, bool v) { c.payload_compensation = v; }));
  table.push_back(number("compensation.payload.mass_kg", "0.0", "kg", 0.0, 1e3, false,
                         [](WrapperConfig& c, double v) { c.payload.mass_kg = v; }));
  table.push_back(
      vector3("compensation.payload.com_m", "in the tip frame", -10.0, 10.0,
              [](WrapperConfig& c) -> Eigen::Vector3d& { return c.payload.com_in_tip; }));
  Option friction{"compensation.friction.model", Kind::kChoice, "none",
                  "none | sigmoid (phi1..3, default robot.yaml) | viscous_coulomb"};
  friction.choices = "none|sigmoid|viscous_coulomb";
  friction.apply = [](WrapperConfig& c, const Value& v) {
    c.friction.model = v.text == "sigmoid"           ? FrictionModel::kSigmoid
                       : v.text == "viscous_coulomb" ? FrictionModel::kViscousCoulomb
                                                     : FrictionModel::kNone;
  };
  table.push_back(friction);
  table.push_back(perJointIn(
      "compensation.friction.phi1", nullptr, "sigmoid: N m",
      [](WrapperConfig& c) -> std::vector<double>& { return c.friction.phi1; }, -kInfinity));
  table.push_back(perJointIn(
      "compensation.friction.phi2", nullptr, "sigmoid: s/rad",
      [](WrapperConfig& c) -> std::vector<double>& { return c.friction.phi2; }, -kInfinity));
  table.push_back(perJointIn(
      "compensation.friction.phi3", nullptr, "sigmoid: rad/s",
      [](WrapperConfig& c) -> std::vector<double>& { return c.friction.phi3; }, -kInfinity));
  table.push_back(
      perJointIn("compensation.friction.viscous", nullptr, "viscous_coulomb: N m s/rad",
                 [](WrapperConfig& c) -> std::vector<double>& { return c.friction.viscous; }));
  table.push_back(
      perJointIn("compensation.friction.coulomb", nullptr, "viscous_coulomb: N m",
                 [](WrapperConfig& c) -> std::vector<double>& { return c.friction.coulomb; }));
  table.push_back(number("compensation.friction.smoothing_velocity", "0.01",
                         "rad/s: tanh(dq / v) replaces sign(dq)", 0.0, kInfinity, true,
                         [](WrapperConfig& c, double v) { c.friction.smoothing_velocity = v; }));
}

// What stands between the control law and the motors: limit springs and torque shaping.
void addLimitAndShapingOptions(std::vector<Option>& table) {
  table.push_back(spaced(flag("soft_limits.enabled", "true", "spring-damper near the URDF limits",
                              [](WrapperConfig& c, bool v) { c.soft_limits.enabled = v; })));
  table.push_back(
      perJointIn("soft_limits.margin_rad", "0.1", "spring starts this far inside each URDF limit",
                 [](WrapperConfig& c) -> std::vector<double>& { return c.soft_limits.margin; }));
  table.push_back(
      perJointIn("soft_limits.stiffness", "100.0", "N m/rad",
                 [](WrapperConfig& c) -> std::vector<double>& { return c.soft_limits.stiffness; }));
  table.push_back(
      perJointIn("soft_limits.damping", "5.0", "N m s/rad",
                 [](WrapperConfig& c) -> std::vector<double>& { return c.soft_limits.damping; }));

  table.push_back(
      spaced(number("filter_alpha", "1.0", "first-order low-pass on the torque; 1 = off", 0.0, 1.0,
                    true, [](WrapperConfig& c, double v) { c.filter_alpha = v; })));
  // 0 would hold every joint's torque where it starts: the controller could not act at all.
  table.push_back(perJoint("torque_rate_limit_nm_per_s", "1000.0", "N m/s per joint", 0.0, true,
                           &WrapperConfig::torque_rate_limit));
  table.push_back(perJoint("effort_limit_nm", nullptr, "default from the URDF <limit effort>", 0.0,
                           true, &WrapperConfig::effort_limit));
  Option saturation{"effort_saturation", Kind::kChoice, "clip",
                    "clip: each joint on its own; scale: the law's torque as a whole, its "
                    "direction kept"};
  saturation.choices = "clip|scale";
  saturation.apply = [](WrapperConfig& c, const Value& v) {
    c.effort_saturation = v.text == "scale" ? EffortSaturation::kScale : EffortSaturation::kClip;
  };
  table.push_back(saturation);
  table.push_back(perJoint("fault_damping", "5.0",
                           "N m s/rad of the FAULT holding torque (gravity + damping)", 0.0, false,
                           &WrapperConfig::fault_damping));
  table.push_back(
      number("frozen_state_timeout_s", "0.1",
             "stale sensor -> FAULT: state bit-identical this long, torque moved > 1 N m; 0: never",
             0.0, 10.0, false, [](WrapperConfig& c, double v) { c.frozen_state_timeout_s = v; }));
}

/// A number kept in one field of a section of the configuration (gain_ramps, passivity, ...).
template <typename Section>
Option sectionNumber(const char* key, const char* default_text, const char* comment,
                     Section WrapperConfig::*section, double Section::*field, double max,
                     bool min_exclusive) {
  return number(key, default_text, comment, 0.0, max, min_exclusive,
                [section, field](WrapperConfig& c, double v) { (c.*section).*field = v; });
}

Option rate(const char* key, const char* default_text, const char* comment,
            double GainRampConfig::*field) {
  return sectionNumber(key, default_text, comment, &WrapperConfig::gain_ramps, field, kInfinity,
                       true);
}

Option energy(const char* key, const char* default_text, const char* comment,
              double PassivityConfig::*field) {
  return sectionNumber(key, default_text, comment, &WrapperConfig::passivity, field, 1e6, false);
}

// What stands between the gains a command asks for and the gains the law sees: rate limits, and
// the energy tank that keeps a streamed stiffness or task-frame schedule from injecting energy.
void addGainOptions(std::vector<Option>& table) {
  table.push_back(spaced(flag("gain_ramps.enabled", "false",
                              "a step in stiffness, damping or task frame becomes a ramp",
                              [](WrapperConfig& c, bool v) { c.gain_ramps.enabled = v; })));
  table.push_back(rate("gain_ramps.translational_stiffness_per_s", "10000.0", "N/m per s",
                       &GainRampConfig::translational_stiffness_per_s));
  table.push_back(rate("gain_ramps.rotational_stiffness_per_s", "1000.0", "N m/rad per s",
                       &GainRampConfig::rotational_stiffness_per_s));
  table.push_back(rate("gain_ramps.joint_stiffness_per_s", "2000.0",
                       "N m/rad per s: joint control and the nullspace",
                       &GainRampConfig::joint_stiffness_per_s));
  table.push_back(rate("gain_ramps.translational_damping_per_s", "1000.0", "N s/m per s",
                       &GainRampConfig::translational_damping_per_s));
  table.push_back(rate("gain_ramps.rotational_damping_per_s", "100.0", "N m s/rad per s",
                       &GainRampConfig::rotational_damping_per_s));
  table.push_back(rate("gain_ramps.joint_damping_per_s", "200.0",
                       "N m s/rad per s: joint control and the nullspace",
                       &GainRampConfig::joint_damping_per_s));
  table.push_back(
      rate("gain_ramps.damping_ratio_per_s", "5.0", "1/s", &GainRampConfig::damping_ratio_per_s));
  table.push_back(rate("gain_ramps.task_frame_rad_per_s", "1.0", "rad/s of the task frame",
                       &GainRampConfig::task_frame_rad_per_s));

  table.push_back(spaced(flag("passivity.enabled", "false",
                              "energy tank: stiffness and task-frame changes only as paid for",
                              [](WrapperConfig& c, bool v) { c.passivity.enabled = v; })));
  table.push_back(energy("passivity.tank_initial_j", "1.0", "J in the tank on activation",
                         &PassivityConfig::tank_initial_j));
  table.push_back(energy("passivity.tank_max_j", "2.0", "J: the damping refills it up to here",
                         &PassivityConfig::tank_max_j));
  table.push_back(
      energy("passivity.tank_min_j", "0.01", "J: never spent below", &PassivityConfig::tank_min_j));
  table.push_back(energy("passivity.nullspace_tank_initial_j", "0.5",
                         "J: the nullspace's own account (Cartesian control)",
                         &PassivityConfig::nullspace_tank_initial_j));
  table.push_back(
      energy("passivity.nullspace_tank_max_j", "1.0", "J", &PassivityConfig::nullspace_tank_max_j));
}

Option guard(const char* key, const char* default_text, const char* comment,
             double StabilityGuardConfig::*field, bool zero_allowed = false) {
  return sectionNumber(key, default_text, comment, &WrapperConfig::stability_guard, field, 1e6,
                       !zero_allowed);
}

// What a running arm must never do, whatever the law and the gains ask.
void addGuardOptions(std::vector<Option>& table) {
  table.push_back(spaced(
      flag("stability_guard.enabled", "true",
           "FAULT on a runaway: overspeed, past a limit, sustained saturation, growing energy",
           [](WrapperConfig& c, bool v) { c.stability_guard.enabled = v; })));
  table.push_back(guard("stability_guard.velocity_factor", "1.0",
                        "FAULT above this times a joint's URDF velocity limit",
                        &StabilityGuardConfig::velocity_factor));
  table.push_back(guard("stability_guard.velocity_time_s", "0.005", "s above it before FAULT",
                        &StabilityGuardConfig::velocity_time_s, true));
  table.push_back(guard("stability_guard.position_margin_rad", "0.05",
                        "rad | m past a URDF position limit: FAULT",
                        &StabilityGuardConfig::position_margin_rad, true));
  table.push_back(guard("stability_guard.saturation_time_s", "1.0",
                        "s a joint may sit at its effort limit before FAULT; 0: never",
                        &StabilityGuardConfig::saturation_time_s, true));
  table.push_back(guard("stability_guard.energy_window_s", "0.25",
                        "s per window of the energy rule (an oscillation growing while the "
                        "command holds still); 0: off",
                        &StabilityGuardConfig::energy_window_s, true));
  table.push_back(number("stability_guard.energy_growth", "4.0",
                         "times (above 1) the oscillation's energy grows, window over window, "
                         "before FAULT",
                         1.0, 1e6, true,
                         [](WrapperConfig& c, double v) { c.stability_guard.energy_growth = v; }));
  table.push_back(guard("stability_guard.energy_floor_j", "0.05",
                        "J (joint-inertia weighted) the grown energy must exceed",
                        &StabilityGuardConfig::energy_floor_j, true));
}

// The external wrench, estimated from the joints' momentum (pipeline/momentum_observer.hpp).
void addObserverOptions(std::vector<Option>& table) {
  table.push_back(spaced(
      flag("observer.enabled", "false",
           "estimate the external wrench at the TCP from the joints' momentum (the state's wrench)",
           [](WrapperConfig& c, bool v) { c.observer.enabled = v; })));
  table.push_back(sectionNumber("observer.gain_per_s", "50.0",
                                "1/s: the estimate's bandwidth (time constant 1/gain)",
                                &WrapperConfig::observer, &ObserverConfig::gain_per_s, 1e4, true));
  table.push_back(
      sectionNumber("observer.damping", "0.001",
                    "lambda of the pseudo-inverse (J J^T + lambda^2 I)^-1 J near a singularity",
                    &WrapperConfig::observer, &ObserverConfig::damping, 1.0, false));
  table.push_back(flag("observer.measured_torque", "false",
                       "use the measured joint torque (torque-sensing arms) instead of the "
                       "commanded one",
                       [](WrapperConfig& c, bool v) { c.observer.measured_torque = v; }));
}

// The wrist force/torque sensor's reading (pipeline/cycle_wrench.cpp).
void addWrenchSensorOptions(std::vector<Option>& table) {
  table.push_back(spaced(
      number("wrench_sensor.filter_hz", "0.0",
             "Hz: first-order low-pass on the wrist sensor's reading (tool weight off); 0: off",
             0.0, 1e4, false, [](WrapperConfig& c, double v) { c.wrench_sensor.filter_hz = v; })));
}

// Force along task axes and the contact-force limit (pipeline/force_axes.hpp).
void addForceControlOptions(std::vector<Option>& table) {
  Option source{"force_control.source", Kind::kChoice, "auto",
                "wrench the force loop reads: auto (observer when it runs, else the wrist "
                "sensor) | observer | sensor"};
  source.choices = "auto|observer|sensor";
  source.blank_line_before = true;
  source.apply = [](WrapperConfig& c, const Value& v) {
    c.force_control.source = v.text == "observer" ? ForceSource::kObserver
                             : v.text == "sensor" ? ForceSource::kSensor
                                                  : ForceSource::kAuto;
  };
  table.push_back(source);
  const auto force = [](const char* key, const char* default_text, const char* comment, double max,
                        bool min_exclusive, double ForceControlConfig::*field) {
    return sectionNumber(key, default_text, comment, &WrapperConfig::force_control, field, max,
                         min_exclusive);
  };
  table.push_back(force("force_control.proportional_gain", "0.2",
                        "k_p: N of push per N of force error on a force axis", 100.0, false,
                        &ForceControlConfig::proportional_gain));
  table.push_back(force("force_control.integral_gain_per_s", "10.0",
                        "k_i [1/s]: the integral of the force error", 1e3, false,
                        &ForceControlConfig::integral_gain_per_s));
  table.push_back(force("force_control.integral_limit_n", "20.0",
                        "N: bound of the integral term on a force axis (anti-windup)", 1e4, false,
                        &ForceControlConfig::integral_limit_n));
  table.push_back(force("force_control.integral_limit_n_m", "2.0", "N m: ... on a torque axis", 1e3,
                        false, &ForceControlConfig::integral_limit_n_m));
  table.push_back(force("force_control.max_speed_m_per_s", "0.1",
                        "m/s: faster along a force axis, the push fades out (gone at twice this)",
                        10.0, true, &ForceControlConfig::max_speed_m_per_s));
  table.push_back(force("force_control.max_angular_speed_rad_per_s", "0.5",
                        "rad/s: ... about a torque axis", 20.0, true,
                        &ForceControlConfig::max_angular_speed_rad_per_s));
  table.push_back(vector3("force_control.contact_force_limit_n",
                          "N along task x y z the TCP may exert: the reference is pulled back "
                          "above it; 0: none",
                          0.0, 1e4, [](WrapperConfig& c) -> Eigen::Vector3d& {
                            return c.force_control.contact_force_limit_n;
                          }));
  table.push_back(vector3("force_control.contact_torque_limit_n_m", "N m about task x y z; 0: none",
                          0.0, 1e4, [](WrapperConfig& c) -> Eigen::Vector3d& {
                            return c.force_control.contact_torque_limit_n_m;
                          }));
  table.push_back(force("force_control.limit_bandwidth_hz", "10.0",
                        "Hz: how fast the pull-back settles the force at its limit", 100.0, true,
                        &ForceControlConfig::limit_bandwidth_hz));
}

// What the cycle sends the drives: a torque, a per-joint PD command, or (admittance) a position
// or velocity (pipeline/output_stage.hpp).
void addOutputOptions(std::vector<Option>& table) {
  Option mode{"output.mode", Kind::kChoice, "torque",
              "torque | joint_pd (onboard PD) | position, velocity (admittance)"};
  mode.choices = "torque|joint_pd|position|velocity";
  mode.blank_line_before = true;
  mode.apply = [](WrapperConfig& c, const Value& v) {
    for (const OutputMode candidate : kOutputModes) {
      if (v.text == toString(candidate)) {
        c.output.mode = candidate;
      }
    }
  };
  table.push_back(mode);
  const auto admittance = [](const char* key, const char* default_text, const char* comment,
                             double max, bool min_exclusive, double AdmittanceConfig::*field) {
    return number(key, default_text, comment, 0.0, max, min_exclusive,
                  [field](WrapperConfig& c, double v) { c.output.admittance.*field = v; });
  };
  table.push_back(vector3(
      "output.admittance.added_mass_kg",
      "kg added to the arm's own inertia at the TCP, along task x y z", 0.0, 1e4,
      [](WrapperConfig& c) -> Eigen::Vector3d& { return c.output.admittance.added_mass_kg; }));
  table.push_back(vector3("output.admittance.added_inertia_kg_m2",
                          "kg m^2 added at the TCP, about task x y z", 0.0, 1e4,
                          [](WrapperConfig& c) -> Eigen::Vector3d& {
                            return c.output.admittance.added_inertia_kg_m2;
                          }));
  table.push_back(admittance("output.admittance.velocity_factor", "0.5",
                             "joint speed bound: this times the URDF velocity limit", 1.0, true,
                             &AdmittanceConfig::velocity_factor));
  table.push_back(admittance("output.admittance.max_acceleration_rad_per_s2", "100.0",
                             "joint acceleration bound: a net, far above the law's", 1e5, true,
                             &AdmittanceConfig::max_acceleration_rad_per_s2));
  table.push_back(admittance("output.admittance.max_tracking_error_rad", "0.05",
                             "the virtual arm stays this close to the measured arm", 10.0, true,
                             &AdmittanceConfig::max_tracking_error_rad));
  table.push_back(admittance("output.admittance.velocity_correction_per_s", "10.0",
                             "velocity mode: 1/s x (virtual - measured), added", 1e3, false,
                             &AdmittanceConfig::velocity_correction_per_s));
}

// The sections are added in the order the YAML file prints them; the order is part of the file.
std::vector<Option> makeTable() {
  std::vector<Option> table;
  addCommandOptions(table);
  addCompensationOptions(table);
  addLimitAndShapingOptions(table);
  addGainOptions(table);
  addGuardOptions(table);
  addObserverOptions(table);
  addWrenchSensorOptions(table);
  addForceControlOptions(table);
  addOutputOptions(table);
  return table;
}

}  // namespace

std::span<const Option> table() {
  static const std::vector<Option> kTable = makeTable();
  return kTable;
}

}  // namespace comply::pipeline::options
