#pragma once
// The controller file's options, declared once. Each row is one option: the member it fills,
// its key in the file, its default, its range and the comment that documents it. From the rows
// follow the members of the configuration structs (config.hpp, momentum_observer.hpp,
// force_axes.hpp) with their defaults, the parser's reading and range checks (config.cpp),
// `comply config --defaults` (the documented file) and the ROS 2 controllers' parameter
// declarations (config_parameters.hpp). A new option is one row here and the code that reads it.
//
// A table is a macro over the row kinds, each itself a macro the user defines:
//   NUMBER(member, key, default, lower, min, max, comment)   double; lower: kAtLeast | kAbove min
//   FLAG(member, key, default, comment)                      bool
//   CHOICE(member, key, Enum, default, comment)              enum class named by kEnumNames
//                                                            (enum_names.hpp); default: its
//                                                            enumerator
//   VECTOR3(member, key, min, max, comment)                  Eigen::Vector3d, zero by default
//   PER_JOINT(member, key, default, lower, min, comment)     one number (every joint) or one per
//                                                            joint; std::vector<double>
//   PER_JOINT_UNSET(member, key, lower, min, comment)        the same, without a default (the
//                                                            comment says what then)
// Tables list their rows in the order of the documented file; each is one block there.
//
// Comments inside the tables are /* */: a // comment would swallow the line continuation. The
// rows name kNoLimit, kAtLeast, kAbove and M_PI, which the expansion that reads ranges defines
// (config_options.cpp); the struct expansion ignores them. Defaults are literals: the documented
// file prints them as written.

// What the wrapper accepts from a command source, and when it stops waiting for one
// (WrapperConfig).
#define COMPLY_COMMAND_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  NUMBER(command_timeout_s, "command_timeout_s", 0.5, kAtLeast, 0.0, kNoLimit,            \
         "no command for this long -> timeout_behavior; 0: never")                        \
  CHOICE(timeout_behavior, "timeout_behavior", TimeoutBehavior, kHold,                    \
         "hold: keep the last pose, stop its motion; reanchor: measured pose")            \
  NUMBER(chunk_blend_time_s, "chunk_blend_time_s", 0.1, kAtLeast, 0.0, 10.0,              \
         "s over which a new timed chunk takes over from the reference in force")

// Limits on a command against the measured arm and the host's clock (ValidationConfig).
#define COMPLY_VALIDATION_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)       \
  NUMBER(quaternion_tolerance, "validation.quaternion_tolerance", 1.0e-3, kAbove, 0.0, 0.5,        \
         "|norm - 1| renormalised below, rejected above")                                          \
  NUMBER(max_position_jump_m, "validation.max_position_jump_m", 0.10, kAbove, 0.0, kNoLimit,       \
         "target vs measured TCP position")                                                        \
  NUMBER(max_orientation_jump_rad, "validation.max_orientation_jump_rad", 0.60, kAbove, 0.0, M_PI, \
         "target vs measured TCP orientation")                                                     \
  NUMBER(max_joint_jump_rad, "validation.max_joint_jump_rad", 0.50, kAbove, 0.0, kNoLimit,         \
         "joint target vs measured position (joint commands)")                                     \
  NUMBER(max_nullspace_jump_rad, "validation.max_nullspace_jump_rad", 0.50, kAbove, 0.0, kNoLimit, \
         "nullspace target vs measured position, joints with nullspace stiffness (Cartesian)")     \
  NUMBER(max_wn_period, "validation.max_wn_period", 0.35, kAtLeast, 0.0, 0.43,                     \
         "largest w_n T a stiffness or damping may give on the arm's lightest inertia (0: no "     \
         "bound)")                                                                                 \
  NUMBER(                                                                                          \
      rate_limit_swing_nm, "validation.rate_limit_swing_nm", 5.0, kAtLeast, 0.0, kNoLimit,         \
      "N m of torque swing a stiffness must pass through the torque-rate limit without a limit "   \
      "cycle: sqrt(K / m) <= rate limit / this (output.mode torque; 0: no bound)")                 \
  NUMBER(max_stamp_lead_s, "validation.max_stamp_lead_s", 1.0, kAbove, 0.0, kNoLimit,              \
         "s a command's stamp, or a chunk's first waypoint, may be ahead of the host's clock")     \
  NUMBER(max_chunk_acceleration_m_per_s2, "validation.max_chunk_acceleration_m_per_s2", 13.0,      \
         kAtLeast, 0.0, kNoLimit,                                                                  \
         "m/s^2 a chunk's curve may ask of the TCP (FR3 datasheet: 13); 0: no bound")              \
  NUMBER(max_chunk_angular_acceleration_rad_per_s2,                                                \
         "validation.max_chunk_angular_acceleration_rad_per_s2", 25.0, kAtLeast, 0.0, kNoLimit,    \
         "rad/s^2 a chunk's curve may ask of the TCP (FR3 datasheet: 25); 0: no bound")            \
  NUMBER(max_chunk_joint_acceleration_rad_per_s2,                                                  \
         "validation.max_chunk_joint_acceleration_rad_per_s2", 10.0, kAtLeast, 0.0, kNoLimit,      \
         "rad/s^2 a joint chunk's curve may ask of each joint (FR3 datasheet: 10 to 20; the low "  \
         "end); 0: no bound")

// Model-based torques added to the law's: gravity and a held payload (WrapperConfig).
#define COMPLY_COMPENSATION_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  FLAG(gravity_compensation, "compensation.gravity", true, "g(q) from the URDF")               \
  FLAG(payload_compensation, "compensation.payload.enabled", false, "a load held at the tip")

// The payload held at the tip (PayloadConfig).
#define COMPLY_PAYLOAD_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  NUMBER(mass_kg, "compensation.payload.mass_kg", 0.0, kAtLeast, 0.0, 1e3, "kg")          \
  VECTOR3(com_in_tip, "compensation.payload.com_m", -10.0, 10.0, "in the tip frame")

// Joint friction (FrictionConfig; compensation.hpp has the formulas).
#define COMPLY_FRICTION_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)         \
  CHOICE(model, "compensation.friction.model", FrictionModel, kNone,                               \
         "none | sigmoid (phi1..3, default robot.yaml) | viscous_coulomb")                         \
  PER_JOINT_UNSET(phi1, "compensation.friction.phi1", kAtLeast, -kNoLimit, "sigmoid: N m")         \
  PER_JOINT_UNSET(phi2, "compensation.friction.phi2", kAtLeast, -kNoLimit, "sigmoid: s/rad")       \
  PER_JOINT_UNSET(phi3, "compensation.friction.phi3", kAtLeast, -kNoLimit, "sigmoid: rad/s")       \
  PER_JOINT_UNSET(viscous, "compensation.friction.viscous", kAtLeast, 0.0,                         \
                  "viscous_coulomb: N m s/rad")                                                    \
  PER_JOINT_UNSET(coulomb, "compensation.friction.coulomb", kAtLeast, 0.0, "viscous_coulomb: N m") \
  NUMBER(smoothing_velocity, "compensation.friction.smoothing_velocity", 0.01, kAbove, 0.0,        \
         kNoLimit, "rad/s: tanh(dq / v) replaces sign(dq)")

// Spring-dampers near the URDF limits (SoftLimitConfig).
#define COMPLY_SOFT_LIMIT_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  FLAG(enabled, "soft_limits.enabled", true, "spring-damper near the URDF limits")           \
  PER_JOINT(margin, "soft_limits.margin_rad", 0.1, kAtLeast, 0.0,                            \
            "spring starts this far inside each URDF limit")                                 \
  PER_JOINT(stiffness, "soft_limits.stiffness", 100.0, kAtLeast, 0.0, "N m/rad")             \
  PER_JOINT(damping, "soft_limits.damping", 5.0, kAtLeast, 0.0, "N m s/rad")

// What shapes the torque on its way to the motors (WrapperConfig). A torque-rate limit of 0
// would hold every joint's torque where it starts: the controller could not act at all.
#define COMPLY_SHAPING_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)       \
  NUMBER(filter_alpha, "filter_alpha", 1.0, kAbove, 0.0, 1.0,                                   \
         "first-order low-pass on the torque; 1 = off")                                         \
  PER_JOINT(torque_rate_limit, "torque_rate_limit_nm_per_s", 1000.0, kAbove, 0.0,               \
            "N m/s per joint")                                                                  \
  PER_JOINT_UNSET(effort_limit, "effort_limit_nm", kAbove, 0.0,                                 \
                  "default from the URDF <limit effort>")                                       \
  CHOICE(effort_saturation, "effort_saturation", EffortSaturation, kClip,                       \
         "clip: each joint on its own; scale: the law's torque as a whole, its direction kept") \
  PER_JOINT(fault_damping, "fault_damping", 5.0, kAtLeast, 0.0,                                 \
            "N m s/rad: the least braking of the FAULT's controlled stop (safety.md)")          \
  NUMBER(frozen_state_timeout_s, "frozen_state_timeout_s", 0.1, kAtLeast, 0.0, 10.0,            \
         "stale sensor -> FAULT: state bit-identical this long, torque moved > 1 N m; 0: never")

// Rate limits on the gains the law sees (GainRampConfig). Each bounds every entry of its matrix
// or vector per second; matrices move along the straight line to the command, so they stay
// symmetric positive semi-definite.
#define COMPLY_GAIN_RAMP_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)        \
  FLAG(enabled, "gain_ramps.enabled", false,                                                       \
       "a step in stiffness, damping or task frame becomes a ramp")                                \
  NUMBER(translational_stiffness_per_s, "gain_ramps.translational_stiffness_per_s", 10000.0,       \
         kAbove, 0.0, kNoLimit, "N/m per s")                                                       \
  NUMBER(rotational_stiffness_per_s, "gain_ramps.rotational_stiffness_per_s", 1000.0, kAbove, 0.0, \
         kNoLimit, "N m/rad per s")                                                                \
  NUMBER(joint_stiffness_per_s, "gain_ramps.joint_stiffness_per_s", 2000.0, kAbove, 0.0, kNoLimit, \
         "N m/rad per s: joint control and the nullspace")                                         \
  NUMBER(translational_damping_per_s, "gain_ramps.translational_damping_per_s", 1000.0, kAbove,    \
         0.0, kNoLimit, "N s/m per s")                                                             \
  NUMBER(rotational_damping_per_s, "gain_ramps.rotational_damping_per_s", 100.0, kAbove, 0.0,      \
         kNoLimit, "N m s/rad per s")                                                              \
  NUMBER(joint_damping_per_s, "gain_ramps.joint_damping_per_s", 200.0, kAbove, 0.0, kNoLimit,      \
         "N m s/rad per s: joint control and the nullspace")                                       \
  NUMBER(damping_ratio_per_s, "gain_ramps.damping_ratio_per_s", 5.0, kAbove, 0.0, kNoLimit, "1/s") \
  NUMBER(task_frame_rad_per_s, "gain_ramps.task_frame_rad_per_s", 1.0, kAbove, 0.0, kNoLimit,      \
         "rad/s of the task frame")

// The energy tank (PassivityConfig; gain_guard.hpp): it pays for the energy a stiffness or
// task-frame change injects into the springs and refuses, smoothly, what it cannot pay.
#define COMPLY_PASSIVITY_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)       \
  FLAG(enabled, "passivity.enabled", false,                                                       \
       "energy tank: stiffness and task-frame changes only as paid for")                          \
  NUMBER(tank_initial_j, "passivity.tank_initial_j", 1.0, kAtLeast, 0.0, 1e6,                     \
         "J in the tank on activation")                                                           \
  NUMBER(tank_max_j, "passivity.tank_max_j", 2.0, kAtLeast, 0.0, 1e6,                             \
         "J: the damping refills it up to here")                                                  \
  NUMBER(tank_min_j, "passivity.tank_min_j", 0.01, kAtLeast, 0.0, 1e6, "J: never spent below")    \
  NUMBER(nullspace_tank_initial_j, "passivity.nullspace_tank_initial_j", 0.5, kAtLeast, 0.0, 1e6, \
         "J: the nullspace's own account (Cartesian control)")                                    \
  NUMBER(nullspace_tank_max_j, "passivity.nullspace_tank_max_j", 1.0, kAtLeast, 0.0, 1e6, "J")

// The stability guard (StabilityGuardConfig): what a running arm must never do, whatever the law
// and the gains ask, each ending in FAULT with a named reason. The energy rule (energy_watch.hpp)
// trips on an oscillation whose energy grows energy_growth times over windows of
// energy_window_s, each higher than the last, while the command holds still.
#define COMPLY_STABILITY_GUARD_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  FLAG(enabled, "stability_guard.enabled", true,                                                  \
       "FAULT on a runaway: overspeed, past a limit, sustained saturation, growing energy")       \
  NUMBER(velocity_factor, "stability_guard.velocity_factor", 1.0, kAbove, 0.0, 1e6,               \
         "FAULT above this times a joint's URDF velocity limit")                                  \
  NUMBER(velocity_time_s, "stability_guard.velocity_time_s", 0.005, kAtLeast, 0.0, 1e6,           \
         "s above it before FAULT")                                                               \
  NUMBER(position_margin_rad, "stability_guard.position_margin_rad", 0.05, kAtLeast, 0.0, 1e6,    \
         "rad | m past a URDF position limit: FAULT")                                             \
  NUMBER(saturation_time_s, "stability_guard.saturation_time_s", 1.0, kAtLeast, 0.0, 1e6,         \
         "s a joint may sit at its effort limit before FAULT; 0: never")                          \
  NUMBER(energy_window_s, "stability_guard.energy_window_s", 0.25, kAtLeast, 0.0, 1e6,            \
         "s per window of the energy rule (an oscillation growing while the command holds "       \
         "still); 0: off")                                                                        \
  NUMBER(energy_growth, "stability_guard.energy_growth", 4.0, kAbove, 1.0, 1e6,                   \
         "times (above 1) the oscillation's energy grows, window over window, before FAULT")      \
  NUMBER(energy_floor_j, "stability_guard.energy_floor_j", 0.05, kAtLeast, 0.0, 1e6,              \
         "J (joint-inertia weighted) the grown energy must exceed")

// The motion governor (GovernorConfig; motion_governor.hpp): prevents what the stability guard
// detects. The law's torque is scaled down, its direction kept, as a joint nears its share of its
// URDF speed or the TCP nears its speeds, and a joint or the TCP past them is braked; the
// overspeed FAULT (stability_guard.velocity_factor) stays as the last line. Chunks are checked
// against the same speeds at the intake.
#define COMPLY_GOVERNOR_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)        \
  FLAG(enabled, "governor.enabled", true,                                                         \
       "no accepted command drives a joint or the TCP past the speeds below")                     \
  NUMBER(velocity_fraction, "governor.velocity_fraction", 0.8, kAbove, 0.0, 1.0,                  \
         "share of each joint's URDF velocity limit no joint passes; below "                      \
         "stability_guard.velocity_factor")                                                       \
  NUMBER(tcp_speed_m_per_s, "governor.tcp_speed_m_per_s", 1.0, kAtLeast, 0.0, 10.0,               \
         "m/s the TCP does not pass (Cartesian laws); 0: no bound")                               \
  NUMBER(tcp_angular_speed_rad_per_s, "governor.tcp_angular_speed_rad_per_s", 2.5, kAtLeast, 0.0, \
         20.0, "rad/s the TCP does not pass (Cartesian laws); 0: no bound")

// Virtual walls and boxes (WallConfig; virtual_walls.hpp): the planes themselves are the lists
// walls: and boxes: (read outside the table: each entry is a point and a normal, or two corners).
// The barrier brakes a TCP that approaches a wall within brake_distance_m, passively (only while
// it moves toward the wall); the reference is kept inside the walls whatever the gains.
#define COMPLY_WALL_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)             \
  NUMBER(brake_distance_m, "wall.brake_distance_m", 0.05, kAbove, 0.0, 1.0,                        \
         "m from a wall (walls:, boxes:) where the barrier starts braking a TCP moving toward it") \
  NUMBER(stiffness_n_per_m, "wall.stiffness_n_per_m", 2000.0, kAtLeast, 0.0, 1e5,                  \
         "N/m x the depth into the braking zone, while the TCP approaches the wall")               \
  NUMBER(damping_n_s_per_m, "wall.damping_n_s_per_m", 200.0, kAtLeast, 0.0, 1e4,                   \
         "N s/m x the TCP's approach speed within the braking zone")

// The contact reflex (ReflexConfig; contact_reflex.hpp): a contact wrench above the thresholds
// for debounce_s is answered by a hold, a retreat or a FAULT. The thresholds are per task axis
// (an ellipsoid: equal entries trip on the norm); a command raises them for a phase of its task
// (reflex_force, reflex_torque) up to the ceilings, which only this file sets.
#define COMPLY_REFLEX_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)         \
  FLAG(enabled, "reflex.enabled", false,                                                         \
       "react to a contact wrench above its thresholds (observer.enabled, or a wrist sensor)")   \
  CHOICE(reaction, "reflex.reaction", ReflexReaction, kHold,                                     \
         "hold: the measured pose, motion stopped | retreat: back off along the contact force, " \
         "then hold | fault: FAULT")                                                             \
  NUMBER(force_n, "reflex.force_n", 20.0, kAbove, 0.0, 1e4,                                      \
         "N of contact force along any task axis that trips it (a command's reflex_force: per "  \
         "axis)")                                                                                \
  NUMBER(torque_nm, "reflex.torque_nm", 5.0, kAbove, 0.0, 1e3,                                   \
         "N m of contact torque about any task axis that trips it (a command's reflex_torque)")  \
  NUMBER(max_force_n, "reflex.max_force_n", 60.0, kAbove, 0.0, 1e4,                              \
         "N: the most a command may raise reflex_force to, on any axis")                         \
  NUMBER(max_torque_nm, "reflex.max_torque_nm", 15.0, kAbove, 0.0, 1e3,                          \
         "N m: the most a command may raise reflex_torque to, on any axis")                      \
  NUMBER(debounce_s, "reflex.debounce_s", 0.005, kAtLeast, 0.0, 1.0,                             \
         "s the wrench stays above a threshold before it trips (0: the first sample)")           \
  NUMBER(retreat_m, "reflex.retreat_m", 0.05, kAtLeast, 0.0, 0.3,                                \
         "m a retreat backs off along the contact force")                                        \
  NUMBER(retreat_speed_m_per_s, "reflex.retreat_speed_m_per_s", 0.1, kAbove, 0.0, 0.5,           \
         "m/s of the retreat")                                                                   \
  NUMBER(hold_stiffness_fraction, "reflex.hold_stiffness_fraction", 1.0, kAtLeast, 0.0, 1.0,     \
         "the stiffness in force scaled by this when it holds or retreats (1: unchanged)")

// The TCP's speed along its motion bounded by what an unexpected contact may cost (power and
// force limiting in the spirit of ISO/TS 15066; ContactSpeedConfig; contact_speed.hpp,
// body_regions.hpp): v_max = F / sqrt(mu k), mu the arm's mass along the motion at this pose (the
// rotors' inertia and the declared payload included). Cartesian laws, torque or joint_pd output.
#define COMPLY_CONTACT_SPEED_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)   \
  FLAG(enabled, "contact_speed.enabled", false,                                                   \
       "the TCP no faster along its motion than a contact with body_region may take")             \
  CHOICE(                                                                                         \
      body_region, "contact_speed.body_region", BodyRegion, kHands,                               \
      "skull_forehead | face | neck | back_shoulders | chest | abdomen | pelvis | upper_arms | "  \
      "lower_arms | hands | thighs | lower_legs (ISO/TS 15066 Annex A)")                          \
  CHOICE(contact, "contact_speed.contact", ContactKind, kQuasiStatic,                             \
         "quasi_static: the region's quasi-static force | transient: twice it (an impact; not "   \
         "for skull_forehead or face)")                                                           \
  NUMBER(force_limit_n, "contact_speed.force_limit_n", 0.0, kAtLeast, 0.0, 1e4,                   \
         "N a contact may reach, in place of the region's; 0: the region's")                      \
  NUMBER(stiffness_n_per_m, "contact_speed.stiffness_n_per_m", 0.0, kAtLeast, 0.0, 1e7,           \
         "N/m of what the TCP meets, in place of the region's; 0: the region's")                  \
  FLAG(body_mass, "contact_speed.body_mass", false,                                               \
       "count the region's effective mass (a free body part: faster, less conservative); false: " \
       "the arm's alone (clamped)")

// The external wrench estimated from the joints' momentum (ObserverConfig).
#define COMPLY_OBSERVER_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  FLAG(enabled, "observer.enabled", false,                                                 \
       "estimate the external wrench at the TCP from the joints' momentum (the state's "   \
       "wrench)")                                                                          \
  NUMBER(gain_per_s, "observer.gain_per_s", 50.0, kAbove, 0.0, 1e4,                        \
         "1/s: the estimate's bandwidth (time constant 1/gain)")                           \
  NUMBER(damping, "observer.damping", 0.001, kAtLeast, 0.0, 1.0,                           \
         "lambda of the pseudo-inverse (J J^T + lambda^2 I)^-1 J near a singularity")      \
  FLAG(measured_torque, "observer.measured_torque", false,                                 \
       "use the measured joint torque (torque-sensing arms) instead of the commanded one")

// The wrist force/torque sensor's reading (WrenchSensorConfig; wrist_sensor.hpp).
#define COMPLY_WRENCH_SENSOR_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)  \
  NUMBER(filter_hz, "wrench_sensor.filter_hz", 0.0, kAtLeast, 0.0, 1e4,                          \
         "Hz: first-order low-pass on the wrist sensor's reading (tool weight off); 0: off")     \
  NUMBER(rest_force_tolerance_n, "wrench_sensor.rest_force_tolerance_n", 2.0, kAbove, 0.0, 1e4,  \
         "N the reading at rest may keep at activation (tool and tare off), where it moves the " \
         "arm; above: FAULT")                                                                    \
  NUMBER(rest_torque_tolerance_n_m, "wrench_sensor.rest_torque_tolerance_n_m", 0.2, kAbove, 0.0, \
         1e3, "N m: the same, of its torque")                                                    \
  NUMBER(rest_payload_fraction, "wrench_sensor.rest_payload_fraction", 0.1, kAtLeast, 0.0, 1.0,  \
         "share of the declared tool's weight (and its moment) added to both tolerances")        \
  NUMBER(observer_tolerance_n, "wrench_sensor.observer_tolerance_n", 0.0, kAtLeast, 0.0, 1e4,    \
         "N the force may differ from the momentum observer's for 0.1 s (both running); 0: "     \
         "not compared")

// Force along task axes and the contact-force limit (ForceControlConfig; force_axes.hpp).
#define COMPLY_FORCE_CONTROL_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  CHOICE(source, "force_control.source", ForceSource, kAuto,                                    \
         "wrench the force loop reads: auto (observer when it runs, else the wrist sensor) | "  \
         "observer | sensor")                                                                   \
  NUMBER(proportional_gain, "force_control.proportional_gain", 0.2, kAtLeast, 0.0, 100.0,       \
         "k_p: N of push per N of force error on a force axis")                                 \
  NUMBER(integral_gain_per_s, "force_control.integral_gain_per_s", 10.0, kAtLeast, 0.0, 1e3,    \
         "k_i [1/s]: the integral of the force error")                                          \
  NUMBER(integral_limit_n, "force_control.integral_limit_n", 20.0, kAtLeast, 0.0, 1e4,          \
         "N: bound of the integral term on a force axis (anti-windup)")                         \
  NUMBER(integral_limit_n_m, "force_control.integral_limit_n_m", 2.0, kAtLeast, 0.0, 1e3,       \
         "N m: ... on a torque axis")                                                           \
  NUMBER(max_speed_m_per_s, "force_control.max_speed_m_per_s", 0.1, kAbove, 0.0, 10.0,          \
         "m/s: faster along a force axis, the push fades out (gone at twice this)")             \
  NUMBER(max_angular_speed_rad_per_s, "force_control.max_angular_speed_rad_per_s", 0.5, kAbove, \
         0.0, 20.0, "rad/s: ... about a torque axis")                                           \
  VECTOR3(contact_force_limit_n, "force_control.contact_force_limit_n", 0.0, 1e4,               \
          "N along task x y z the TCP may exert: the reference is pulled back above it; 0: "    \
          "none")                                                                               \
  VECTOR3(contact_torque_limit_n_m, "force_control.contact_torque_limit_n_m", 0.0, 1e4,         \
          "N m about task x y z; 0: none")                                                      \
  NUMBER(limit_bandwidth_hz, "force_control.limit_bandwidth_hz", 10.0, kAbove, 0.0, 100.0,      \
         "Hz: how fast the pull-back settles the force at its limit")

// What the cycle sends the drives (OutputConfig; output_stage.hpp).
#define COMPLY_OUTPUT_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET) \
  CHOICE(mode, "output.mode", OutputMode, kTorque,                                       \
         "torque | joint_pd (onboard PD) | position, velocity (admittance)")

// Admittance (output.mode position or velocity; AdmittanceConfig): the law's torque, with the
// measured external wrench, drives a virtual arm (the arm's own inertia plus what is added here,
// without gravity or friction) whose motion the arm's position or velocity drives follow. The
// acceleration bound is a net for a wild sensor reading, to be kept well above what the law asks
// (a bound in the loop makes the virtual arm overshoot); the tracking bound is what a blocked or
// lagging arm can wind up; the velocity correction keeps the drives' own integration error from
// accumulating (velocity mode).
#define COMPLY_ADMITTANCE_OPTIONS(NUMBER, FLAG, CHOICE, VECTOR3, PER_JOINT, PER_JOINT_UNSET)       \
  VECTOR3(added_mass_kg, "output.admittance.added_mass_kg", 0.0, 1e4,                              \
          "kg added to the arm's own inertia at the TCP, along task x y z")                        \
  VECTOR3(added_inertia_kg_m2, "output.admittance.added_inertia_kg_m2", 0.0, 1e4,                  \
          "kg m^2 added at the TCP, about task x y z")                                             \
  NUMBER(velocity_factor, "output.admittance.velocity_factor", 0.5, kAbove, 0.0, 1.0,              \
         "joint speed bound: this times the URDF velocity limit")                                  \
  NUMBER(max_acceleration_rad_per_s2, "output.admittance.max_acceleration_rad_per_s2", 100.0,      \
         kAbove, 0.0, 1e5, "joint acceleration bound: a net, far above the law's")                 \
  NUMBER(max_tracking_error_rad, "output.admittance.max_tracking_error_rad", 0.05, kAbove, 0.0,    \
         10.0, "the virtual arm stays this close to the measured arm")                             \
  NUMBER(velocity_correction_per_s, "output.admittance.velocity_correction_per_s", 10.0, kAtLeast, \
         0.0, 1e3, "velocity mode: 1/s x (virtual - measured), added")

// The struct members a table declares, with their defaults:
//   struct GainRampConfig { COMPLY_OPTION_MEMBERS(COMPLY_GAIN_RAMP_OPTIONS) };
#define COMPLY_OPTION_NUMBER_MEMBER(member, key, default_value, lower, min, max, comment) \
  double member = default_value;
#define COMPLY_OPTION_FLAG_MEMBER(member, key, default_value, comment) bool member = default_value;
#define COMPLY_OPTION_CHOICE_MEMBER(member, key, Enum, default_value, comment) \
  Enum member = Enum::default_value;
#define COMPLY_OPTION_VECTOR3_MEMBER(member, key, min, max, comment) \
  Eigen::Vector3d member = Eigen::Vector3d::Zero();
#define COMPLY_OPTION_PER_JOINT_MEMBER(member, key, default_value, lower, min, comment) \
  std::vector<double> member{default_value};
#define COMPLY_OPTION_PER_JOINT_UNSET_MEMBER(member, key, lower, min, comment) \
  std::vector<double> member;
// The same members copied from `from` to `to` (a struct that declares them too):
//   COMPLY_OPTION_COPY(COMPLY_COMMAND_OPTIONS, parameters, config)
#define COMPLY_OPTION_COPY_MEMBER(member, ...) copy_to.member = copy_from.member;
#define COMPLY_OPTION_COPY(TABLE, to, from)                                                \
  {                                                                                        \
    auto& copy_to = (to);                                                                  \
    const auto& copy_from = (from);                                                        \
    TABLE(COMPLY_OPTION_COPY_MEMBER, COMPLY_OPTION_COPY_MEMBER, COMPLY_OPTION_COPY_MEMBER, \
          COMPLY_OPTION_COPY_MEMBER, COMPLY_OPTION_COPY_MEMBER, COMPLY_OPTION_COPY_MEMBER) \
  }
#define COMPLY_OPTION_MEMBERS(TABLE)                                                         \
  TABLE(COMPLY_OPTION_NUMBER_MEMBER, COMPLY_OPTION_FLAG_MEMBER, COMPLY_OPTION_CHOICE_MEMBER, \
        COMPLY_OPTION_VECTOR3_MEMBER, COMPLY_OPTION_PER_JOINT_MEMBER,                        \
        COMPLY_OPTION_PER_JOINT_UNSET_MEMBER)
