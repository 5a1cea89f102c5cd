// The live messages as CDR, field by field in the order of their .msg files (msg/): the commands
// from the schema tables, the others by hand like wire_state.cpp. tests/transport checks every
// message against the bytes CycloneDDS puts on the wire.

#include <Eigen/Core>

#include "cdr_writer.hpp"
#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"
#include "comply/transport/cdr.hpp"

namespace comply::transport {
namespace {

using cdr::Writer;
using schema::FieldKind;

void putStamp(Writer& w, const Stamp& stamp) {
  w.put(stamp.sec);
  w.put(stamp.nanosec);
}

void putHeader(Writer& w, const Header& header) {
  putStamp(w, header.stamp);
  w.putString(header.frame_id);
}

template <std::size_t N>
void putArray(Writer& w, const std::array<double, N>& values) {
  w.putArray(values.data(), N);
}

template <typename T>
void putSequence(Writer& w, const std::vector<T>& values) {
  w.putSequence(values.data(), values.size());
}

template <FieldKind K, typename Value>
void putField(Writer& w, const Value& value) {
  if constexpr (K == FieldKind::kQuaternion) {
    double xyzw[4];
    schema::toXyzw(value, xyzw);
    w.putArray(xyzw, 4);
  } else if constexpr (K == FieldKind::kBlock3) {
    double row_major[9];
    for (int k = 0; k < 9; ++k) {
      row_major[k] = value(k / 3, k % 3);
    }
    w.putArray(row_major, 9);
  } else if constexpr (K == FieldKind::kEnum) {
    w.put(static_cast<std::uint8_t>(value));
  } else if constexpr (K == FieldKind::kJointVector) {
    w.putSequence(value.data(), static_cast<std::size_t>(value.size()));
  } else {
    w.putArray(value.data(), static_cast<std::size_t>(value.size()));
  }
}

#define COMPLY_CDR_FIELD(name, group, kind, type, unit, constraint, role, init, doc) \
  putField<FieldKind::kind>(w, message.command.name);

void putState(Writer& w, const ControllerStateMessage& message) {
  putHeader(w, message.header);
  w.put(static_cast<std::uint8_t>(message.state));
  w.put(static_cast<std::uint8_t>(message.command_kind));
  w.put(message.cycle);
  w.putCount(message.joint_names.size());
  for (const std::string& name : message.joint_names) {
    w.putString(name);
  }
  putSequence(w, message.position);
  putSequence(w, message.velocity);
  putSequence(w, message.effort);
  putSequence(w, message.torque_command);
  putArray(w, message.tcp_position);
  putArray(w, message.tcp_orientation);
  putArray(w, message.tcp_twist);
  putStamp(w, message.reference_stamp);
  w.put(message.reference_fields);
  putArray(w, message.reference_position);
  putArray(w, message.reference_orientation);
  putSequence(w, message.reference_joint_position);
  putArray(w, message.contact_wrench);
  w.put(static_cast<std::uint8_t>(message.contact_wrench_source));
  putArray(w, message.contact_wrench_tcp);
  putArray(w, message.contact_wrench_task);
  w.put(message.contact_wrench_bandwidth_hz);
  w.putBool(message.passivity);
  w.put(message.tank_energy_j);
  w.put(message.nullspace_tank_energy_j);
  w.put(message.energy_injected_j);
  w.put(message.energy_dissipated_j);
  w.put(message.energy_refused_j);
  w.put(message.gain_fraction);
}

void putOutcome(Writer& w, const CommandOutcomeMessage& message) {
  putStamp(w, message.stamp);
  w.put(static_cast<std::uint8_t>(message.command_kind));
  w.put(static_cast<std::uint8_t>(message.outcome));
  w.put(static_cast<std::uint8_t>(message.reason));
  w.put(message.cycle);
  putStamp(w, message.received);
  putStamp(w, message.applied);
  w.putString(message.message);
  w.putArray(message.sender.data(), message.sender.size());
}

void putCartesian(Writer& w, const CartesianCommandMessage& message) {
  putHeader(w, message.header);
  w.put(static_cast<std::uint32_t>(message.command.fields));
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_CDR_FIELD)
}

void putJoint(Writer& w, const JointCommandMessage& message) {
  putHeader(w, message.header);
  w.put(static_cast<std::uint32_t>(message.command.fields));
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_CDR_FIELD)
}

/// A chunk: each waypoint a command whose header.stamp is its time (as the wire writes it).
template <typename Command, typename CommandMessage, typename Message, typename Put>
void putChunk(Writer& w, const Message& message, Put&& put) {
  putHeader(w, message.header);
  w.put(static_cast<std::uint32_t>(message.chunk.fields));
  w.putCount(message.chunk.waypoints.size());
  CommandMessage waypoint{{Stamp{}, message.header.frame_id}, Command{}};
  for (const ChunkWaypoint<Command>& from : message.chunk.waypoints) {
    waypoint.header.stamp = Stamp::fromSeconds(from.time_s);
    waypoint.command = from.command;
    waypoint.command.fields = message.chunk.fields;
    put(w, waypoint);
  }
}

}  // namespace

void encodeCdr(const ControllerStateMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putState(w, message);
  w.finish();
}

void encodeCdr(const CommandOutcomeMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putOutcome(w, message);
  w.finish();
}

void encodeCdr(const DiagnosticsMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putHeader(w, message.header);
  w.put(static_cast<std::uint8_t>(message.state));
  w.put(message.cycles);
  w.put(message.overruns);
  w.put(message.period_s);
  w.put(message.commands_received);
  w.put(message.commands_applied);
  w.put(message.commands_rejected);
  putSequence(w, message.rejections);
  w.put(message.watchdog_timeouts);
  w.put(message.faults);
  w.put(message.rate_limit_hits);
  w.put(message.effort_limit_hits);
  w.put(message.histogram_bin_s);
  putSequence(w, message.compute_time_histogram);
  putSequence(w, message.start_lateness_histogram);
  w.putString(message.last_fault);
  w.putString(message.last_rejection);
  w.putString(message.publisher);
  w.put(message.records_dropped);
  w.putString(message.recording);
  w.putCount(message.outcomes.size());
  for (const CommandOutcomeMessage& outcome : message.outcomes) {
    putOutcome(w, outcome);
  }
  w.finish();
}

void encodeCdr(const CartesianCommandMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putCartesian(w, message);
  w.finish();
}

void encodeCdr(const JointCommandMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putJoint(w, message);
  w.finish();
}

void encodeCdr(const CartesianChunkMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putChunk<CartesianCommand, CartesianCommandMessage>(w, message, putCartesian);
  w.finish();
}

void encodeCdr(const JointChunkMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putChunk<JointCommand, JointCommandMessage>(w, message, putJoint);
  w.finish();
}

void encodeCdr(const RequestMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putHeader(w, message.header);
  w.put(static_cast<std::uint8_t>(message.request));
  w.finish();
}

void encodeCdr(const CycleRecordMessage& message, std::vector<std::uint8_t>& out) {
  Writer w(out);
  putState(w, message.state);
  w.put(message.compute_time_s);
  w.put(message.start_lateness_s);
  w.putCount(message.cartesian_in_force.size());
  for (const CartesianCommandMessage& command : message.cartesian_in_force) {
    putCartesian(w, command);
  }
  w.putCount(message.joint_in_force.size());
  for (const JointCommandMessage& command : message.joint_in_force) {
    putJoint(w, command);
  }
  w.finish();
}

template <>
std::string_view rosTypeName<ControllerStateMessage>() {
  return "comply_msgs/msg/ControllerState";
}
template <>
std::string_view rosTypeName<CommandOutcomeMessage>() {
  return "comply_msgs/msg/CommandOutcome";
}
template <>
std::string_view rosTypeName<DiagnosticsMessage>() {
  return "comply_msgs/msg/Diagnostics";
}
template <>
std::string_view rosTypeName<CartesianCommandMessage>() {
  return "comply_msgs/msg/CartesianCommand";
}
template <>
std::string_view rosTypeName<JointCommandMessage>() {
  return "comply_msgs/msg/JointCommand";
}
template <>
std::string_view rosTypeName<CartesianChunkMessage>() {
  return "comply_msgs/msg/CartesianChunk";
}
template <>
std::string_view rosTypeName<JointChunkMessage>() {
  return "comply_msgs/msg/JointChunk";
}
template <>
std::string_view rosTypeName<RequestMessage>() {
  return "comply_msgs/msg/Request";
}
template <>
std::string_view rosTypeName<CycleRecordMessage>() {
  return "comply_msgs/msg/CycleRecord";
}

}  // namespace comply::transport
