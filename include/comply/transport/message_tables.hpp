#pragma once
// The host's messages declared once: ControllerState, CommandOutcome (and its ChunkTiming),
// Diagnostics and the CommittedRequest a client asks with, a row per field in wire order.
// Everything else follows from these rows:
//   the C++ structs (messages.hpp)                    COMPLY_MESSAGE_BODY
//   CDR both ways (cdr_messages.cpp, cdr_decode.cpp)   Message::visit + cdr_fields.hpp
//   the DDS types idlc builds (wire_state.cpp)         the rows, member by member
//   msg/*.msg and their IDL (`make generated`)        message_text.hpp
//   JSON (`comply echo --json`), Python dicts          Message::visit
// A new field is one row here (and `make generated`); tests/transport/message_tables_test.cpp adds
// one to a copy of a table and shows each spelling follow.
//
// A row: X(Type, member, wire, init, doc)
//   Type    the C++ type (an alias without commas); it decides the wire type: double float64,
//           bool, std::uint8_t or an enum uint8, std::uint32_t, std::uint64_t, std::string, Stamp
//           builtin_interfaces/Time, Header std_msgs/Header, std::array<T, N> T[N],
//           std::vector<T> T[], a message of these tables by its name
//   member  the C++ member
//   wire    the field's name on the wire (ROS 2, DDS, JSON, Python)
//   init    the C++ default
//   doc     the .msg comment: [unit] first where there is one

// clang-format off
#define COMPLY_CONTROLLER_STATE_FIELDS(X) \
  X(Header, header, header, {}, "stamp: host wall-clock time of the cycle; frame_id: the base frame") \
  X(HostState, state, state, HostState::kInactive, "STATE_*: the wrapper's state") \
  X(WireCommandKind, command_kind, command_kind, WireCommandKind::kCartesian, \
    "COMMAND_KIND_*: the command topic the controller takes") \
  X(std::uint64_t, cycle, cycle, 0, "[-] index of the control cycle, 0 for the first") \
  X(Strings, joint_names, joint_names, {}, "the controlled joints, base to tip") \
  X(Doubles, position, position, {}, "[rad | m] measured joint position") \
  X(Doubles, velocity, velocity, {}, "[rad/s | m/s] measured joint velocity") \
  X(Doubles, effort, effort, {}, "[N m | N] measured joint effort") \
  X(Doubles, torque_command, torque_command, {}, "[N m | N] torque the cycle commanded") \
  X(Vector3, tcp_position, tcp_position, {}, "[m] measured TCP position") \
  X(Quaternion, tcp_orientation, tcp_orientation, kIdentityXyzw, \
    "x y z w; [-] measured TCP orientation") \
  X(Vector6, tcp_twist, tcp_twist, {}, "[m/s, rad/s] measured TCP twist, linear first (J dq)") \
  X(Stamp, reference_stamp, reference_stamp, {}, "header.stamp of the newest command in force") \
  X(std::uint64_t, reference_sequence, reference_sequence, 0, \
    "[-] the host's number for that command (CommandOutcome.sequence_number); 0: none taken yet") \
  X(std::uint32_t, reference_fields, reference_fields, 0, "FIELD_* groups any command has set so far") \
  X(Vector3, reference_position, reference_position, {}, \
    "[m] TCP reference in force (Cartesian control)") \
  X(Quaternion, reference_orientation, reference_orientation, kIdentityXyzw, \
    "x y z w; [-] TCP reference orientation (Cartesian control)") \
  X(Doubles, reference_joint_position, reference_joint_position, {}, \
    "[rad | m] joint reference in force (joint control)") \
  X(Vector6, contact_wrench, contact_wrench, {}, \
    "[N, N m] environment on the tool about the TCP, base frame: the momentum observer's " \
    "estimate (observer.enabled), else the hardware's sensor or the simulator's contacts, else 0") \
  X(WrenchSource, contact_wrench_source, contact_wrench_source, WrenchSource::kNone, \
    "WRENCH_SOURCE_*: where contact_wrench comes from (SENSOR: the hardware's, or the " \
    "simulator's contacts)") \
  X(Vector6, contact_wrench_tcp, contact_wrench_tcp, {}, \
    "[N, N m] the same wrench in the TCP frame, force first") \
  X(Vector6, contact_wrench_task, contact_wrench_task, {}, \
    "[N, N m] the same wrench in the task frame in force (Cartesian control; the base frame " \
    "under joint control)") \
  X(double, contact_wrench_bandwidth_hz, contact_wrench_bandwidth, 0.0, \
    "[Hz] first-order bandwidth of the estimate: the observer's gain / 2 pi, the wrist " \
    "sensor's filter; 0: unfiltered or none") \
  X(bool, passivity, passivity, false, \
    "the energy tank is on (controller option passivity.enabled); while it is off, the tank's " \
    "fields below are 0 and gain_fraction 1") \
  X(double, tank_energy_j, tank_energy, 0.0, \
    "[J] energy the tank holds to pay for stiffness and task-frame changes") \
  X(double, nullspace_tank_energy_j, nullspace_tank_energy, 0.0, \
    "[J] the nullspace's own account (Cartesian control)") \
  X(double, energy_injected_j, energy_injected, 0.0, \
    "[J] total paid for stiffness and task-frame changes since activation") \
  X(double, energy_dissipated_j, energy_dissipated, 0.0, \
    "[J] total credited to the tanks from the damping (a lower bound)") \
  X(double, energy_refused_j, energy_refused, 0.0, \
    "[J] what the change the tanks held back this cycle would have injected") \
  X(double, gain_fraction, gain_fraction, 1.0, \
    "[-] fraction of the commanded stiffness change in force (1: all of it)") \
  X(bool, walls, walls, false, \
    "walls or boxes are configured (controller options walls:, boxes:), or the command in force " \
    "sets a workspace box; while none, the fields below are 0") \
  X(double, wall_distance_m, wall_distance, 0.0, \
    "[m] from the measured TCP to the nearest wall or box face; negative past one") \
  X(Vector3, wall_force, wall_force, {}, \
    "[N] the walls' barrier force on the TCP this cycle, base frame (0: not braking)") \
  X(Vector3, workspace_min, workspace_min, {}, \
    "[m] the workspace box the command in force sets, lower corner, base frame (0: none)") \
  X(Vector3, workspace_max, workspace_max, {}, \
    "[m] its upper corner (0: none)") \
  X(bool, reflex, reflex, false, \
    "the contact reflex is on (controller option reflex.enabled); while it is off, the fields " \
    "below are 0") \
  X(Vector3, reflex_force_threshold, reflex_force_threshold, {}, \
    "[N] the contact force along task x y z that trips it (the command's reflex_force, its 0 " \
    "entries the file's reflex.force_n); the base frame's axes under joint control") \
  X(Vector3, reflex_torque_threshold, reflex_torque_threshold, {}, \
    "[N m] the contact torque about task x y z that trips it (reflex_torque, reflex.torque_nm)") \
  X(bool, reflex_tripped, reflex_tripped, false, \
    "it tripped: its hold or retreat refuses commands (REASON_REFLEX_LATCHED), or it faulted, " \
    "until a reset request") \
  X(ReflexReaction, reflex_reaction, reflex_reaction, ReflexReaction::kNone, \
    "REFLEX_*: what it did when it tripped; REFLEX_NONE while it has not") \
  X(Vector6, reflex_wrench, reflex_wrench, {}, \
    "[N, N m] the contact wrench that tripped it, in the task frame then, force first; 0 while " \
    "it has not tripped") \
  X(double, contact_speed_limit_m_per_s, contact_speed_limit, 0.0, \
    "[m/s] the TCP's speed limit along its direction of motion (controller options " \
    "contact_speed.*); 0: the stage is off, or the TCP has not moved yet") \
  X(double, contact_speed_share, contact_speed_share, 1.0, \
    "[-] share of the law's torque the contact-speed limit let through this cycle (1: all of it)") \
  X(double, contact_speed_brake_n, contact_speed_brake, 0.0, \
    "[N] the contact-speed limit's braking force against the TCP's motion this cycle (0: none)")

#define COMPLY_COMMAND_OUTCOME_FIELDS(X) \
  X(Stamp, stamp, stamp, {}, "the command's header.stamp: with the sender, what identifies it") \
  X(WireCommandKind, command_kind, command_kind, WireCommandKind::kCartesian, \
    "ControllerState.COMMAND_KIND_*: the topic it came on") \
  X(Outcome, outcome, outcome, Outcome::kApplied, "OUTCOME_*") \
  X(Reason, reason, reason, Reason::kNone, \
    "REASON_*; REASON_NONE when applied, or for a request the host could not carry out (the " \
    "message says why)") \
  X(std::uint64_t, cycle, cycle, 0, "[-] index of the control cycle that took it (applied)") \
  X(std::uint64_t, sequence_number, sequence_number, 0, \
    "[-] the host's number for it, in the order it accepted commands (applied; " \
    "ControllerState.reference_sequence names the one in force)") \
  X(Stamp, received, received, {}, "host wall clock when the host's reader took it") \
  X(Stamp, applied, applied, {}, \
    "host wall clock at the end of that cycle (applied; a request: when the host carried it " \
    "out)") \
  X(std::string, message, message, {}, "why, naming the field (rejected)") \
  X(Gid, sender, sender, {}, \
    "the sending participant's DDS GUID (the command writer's GUID prefix, entity id " \
    "0x000001c1); with the stamp it names the command; all zero: not known") \
  X(ChunkTimings, chunk, chunk, {}, \
    "a chunk's timing record (0 or 1 entries): one when the chunk took over, or was superseded " \
    "or dropped while it waited for its takeover, before its outcome was sent; none for a " \
    "command, a request, a refused chunk")

#define COMPLY_CHUNK_TIMING_FIELDS(X) \
  X(std::uint64_t, sequence, sequence_number, 0, \
    "[-] the chunk's number (CommandOutcome.sequence_number; `sequence` is an IDL keyword)") \
  X(ChunkEnd, end, end, ChunkEnd::kTookOver, "END_*: how its time in the cycle ended") \
  X(Stamp, observation, observation, {}, \
    "the observation the sender planned it for (the chunk's observation); zero: not given") \
  X(Stamp, received, received, {}, "when the controller's intake accepted it") \
  X(Stamp, takeover, takeover, {}, \
    "when it took over: the cycle it took over in, or the takeover it waited for (the next " \
    "cycle played it); zero: it never did") \
  X(std::uint64_t, takeover_cycle, takeover_cycle, 0, \
    "[-] index of the first cycle that played it (END_TOOK_OVER), else of the cycle that " \
    "ended its wait") \
  X(Stamp, requested_takeover, requested_takeover, {}, \
    "the takeover it asked for (the chunk's takeover); zero: at once") \
  X(Stamp, first_waypoint, first_waypoint, {}, "its first waypoint's time") \
  X(Stamp, last_waypoint, last_waypoint, {}, "its last waypoint's time") \
  X(std::uint32_t, waypoints, waypoints, 0, "[-] its waypoints") \
  X(std::uint32_t, waypoints_past, waypoints_past, 0, \
    "[-] waypoints already past at its takeover: with waypoint 0 at the observation, the delay " \
    "in the chunk's own steps") \
  X(double, position_jump, position_jump, 0.0, \
    "[m | rad] the reference's jump at the seam: TCP position (joint control: the largest " \
    "joint's)") \
  X(double, rotation_jump, rotation_jump, 0.0, "[rad] TCP orientation (0 under joint control)") \
  X(double, velocity_jump, velocity_jump, 0.0, \
    "[m/s | rad/s] TCP velocity (joint control: the largest joint's)") \
  X(double, angular_velocity_jump, angular_velocity_jump, 0.0, \
    "[rad/s] TCP angular velocity (0 under joint control)") \
  X(bool, starved, starved, false, \
    "the chunk before it had run out before it took over (the reference came to rest)") \
  X(double, rest_s, rest, 0.0, "[s] how long the reference had been at rest then (starved)")

#define COMPLY_COMMITTED_REQUEST_FIELDS(X) \
  X(Header, header, header, {}, \
    "stamp: the sender's; with the sender, what names the request in its answer (Committed)") \
  X(Stamp, observation, observation, {}, \
    "the first time asked for, on the host's clock (a state's header.stamp, as a chunk's " \
    "observation)") \
  X(double, dt_s, dt, 0.0, "[s] step between the times asked for: observation + k dt, k < count") \
  X(std::uint32_t, count, count, 0, "[-] times asked for: 1 to 64 (a chunk's most waypoints)")

#define COMPLY_DIAGNOSTICS_FIELDS(X) \
  X(Header, header, header, {}, "stamp: host wall-clock time; frame_id: the host's name") \
  X(HostState, state, state, HostState::kInactive, "ControllerState.STATE_*") \
  X(std::uint64_t, cycles, cycles, 0, "[-] control cycles run") \
  X(std::uint64_t, overruns, overruns, 0, \
    "[-] cycles that missed their deadline: ended after the next one's start (comply run), " \
    "update() longer than the period (ros2_control)") \
  X(double, period_s, period, 0.0, "[s] control period") \
  X(std::uint64_t, commands_received, commands_received, 0, \
    "[-] commands taken from both command topics") \
  X(std::uint64_t, commands_applied, commands_applied, 0, "[-] commands a cycle took") \
  X(std::uint64_t, commands_rejected, commands_rejected, 0, "[-] commands refused, all reasons") \
  X(Counts, rejections, rejections, {}, \
    "[-] refused commands per CommandOutcome.REASON_* (index = reason)") \
  X(std::uint64_t, watchdog_timeouts, watchdog_timeouts, 0, \
    "[-] times no command arrived within the command timeout") \
  X(std::uint64_t, faults, faults, 0, "[-] times the controller entered FAULT") \
  X(std::uint64_t, rate_limit_hits, rate_limit_hits, 0, \
    "[-] joint-cycles clipped by the torque-rate limit") \
  X(std::uint64_t, effort_limit_hits, effort_limit_hits, 0, \
    "[-] joint-cycles clipped by the effort limit") \
  X(std::uint64_t, governor_hits, governor_hits, 0, \
    "[-] cycles the motion governor scaled the law's torque or braked a joint or the TCP") \
  X(std::uint64_t, wall_reference_hits, wall_reference_hits, 0, \
    "[-] cycles the walls moved the law's reference back inside them") \
  X(std::uint64_t, wall_brake_hits, wall_brake_hits, 0, \
    "[-] cycles the walls' barrier braked the TCP approaching a wall") \
  X(std::uint64_t, reflex_trips, reflex_trips, 0, \
    "[-] times the contact reflex tripped (hold, retreat or fault)") \
  X(std::uint64_t, contact_speed_hits, contact_speed_hits, 0, \
    "[-] cycles the contact-speed limit scaled the law's torque or braked the TCP") \
  X(double, histogram_bin_s, histogram_bin, 0.0, "[s] width of one bin of the two histograms") \
  X(Counts, compute_time_histogram, compute_time_histogram, {}, \
    "[-] cycles per bin of compute time; last bin: all above") \
  X(Counts, start_lateness_histogram, start_lateness_histogram, {}, \
    "[-] cycles per bin of cycle-start lateness (wall clock)") \
  X(std::string, last_fault, last_fault, {}, "why the controller last entered FAULT (\"\" if never)") \
  X(std::string, last_rejection, last_rejection, {}, \
    "why the last refused command or request was refused, its reason first (\"\" if none)") \
  X(std::string, publisher, publisher, {}, "the writer holding the command topics (\"\" when none)") \
  X(std::uint64_t, records_dropped, records_dropped, 0, \
    "[-] records the recording refused, its lanes full (--record; 0 without)") \
  X(std::string, recording, recording, {}, \
    "the file being recorded to, or why its recording stopped (\"\" when none)") \
  X(Outcomes, outcomes, outcomes, {}, \
    "every command and request accounted since the previous message, in arrival order")
// clang-format on

/// The members of a message struct from its table, and `visit(self, f)`, which calls
/// f(FieldName, member) for each in wire order (self const or not).
#define COMPLY_MESSAGE_MEMBER(Type, member, wire, init, doc) Type member = init;
#define COMPLY_MESSAGE_VISIT(Type, member, wire, init, doc) \
  f(::comply::transport::FieldName{#wire, doc}, self.member);
#define COMPLY_MESSAGE_BODY(TABLE)       \
  TABLE(COMPLY_MESSAGE_MEMBER)           \
  template <typename Self, typename F>   \
  static void visit(Self& self, F&& f) { \
    TABLE(COMPLY_MESSAGE_VISIT)          \
  }

#include <string_view>

namespace comply::transport {

/// A field as visit() names it.
struct FieldName {
  std::string_view wire;  ///< its name on the wire
  std::string_view doc;   ///< its .msg comment
};

/// A message declared by a table (COMPLY_MESSAGE_BODY).
template <typename T>
concept TableMessage = requires(T& message) {
  T::visit(message, [](FieldName, auto&) {});
};

}  // namespace comply::transport
