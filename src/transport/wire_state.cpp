// ControllerState, Diagnostics and Request on the wire: the hand-written messages, member by
// member (msg/*.msg lists the same members in the same order).

#include <algorithm>
#include <vector>

#include "comply_msgs/msg/ControllerState.h"
#include "comply_msgs/msg/Diagnostics.h"
#include "comply_msgs/msg/Request.h"
#include "wire.hpp"

namespace comply::transport::wire {
namespace {

/// A sequence over a vector the caller keeps alive until dds_write returns.
template <typename Sequence, typename T>
Sequence borrow(const std::vector<T>& values) {
  Sequence sequence{};
  sequence._maximum = sequence._length = static_cast<std::uint32_t>(values.size());
  sequence._buffer = const_cast<T*>(values.data());
  sequence._release = false;
  return sequence;
}

template <typename T, typename Sequence>
std::vector<T> copyOf(const Sequence& sequence) {
  return std::vector<T>(sequence._buffer, sequence._buffer + sequence._length);
}

template <std::size_t N>
void copyArray(const std::array<double, N>& from, double (&to)[N]) {
  std::copy(from.begin(), from.end(), to);
}
template <std::size_t N>
void copyArray(const double (&from)[N], std::array<double, N>& to) {
  std::copy(std::begin(from), std::end(from), to.begin());
}

template <typename WireHeader>
void headerToWire(const Header& header, WireHeader& out) {
  toWireStamp(header.stamp, out.stamp);
  out.frame_id = const_cast<char*>(header.frame_id.c_str());
}

template <typename WireHeader>
void headerFromWire(const WireHeader& in, Header& header) {
  header.stamp = fromWireStamp(in.stamp.sec, in.stamp.nanosec);
  header.frame_id = in.frame_id != nullptr ? in.frame_id : "";
}

std::string text(const char* value) {
  return value != nullptr ? value : "";
}

}  // namespace

template <>
const dds_topic_descriptor_t* Wire<ControllerStateMessage>::descriptor() {
  return &comply_msgs_msg_dds__ControllerState__desc;
}

template <>
dds_return_t Wire<ControllerStateMessage>::write(dds_entity_t writer,
                                                 const ControllerStateMessage& message) {
  comply_msgs_msg_dds__ControllerState_ out{};
  headerToWire(message.header, out.header);
  out.state = static_cast<std::uint8_t>(message.state);
  out.command_kind = static_cast<std::uint8_t>(message.command_kind);
  out.cycle = message.cycle;
  std::vector<char*> names;
  for (const std::string& name : message.joint_names) {
    names.push_back(const_cast<char*>(name.c_str()));
  }
  out.joint_names = borrow<dds_sequence_string>(names);
  out.position = borrow<dds_sequence_double>(message.position);
  out.velocity = borrow<dds_sequence_double>(message.velocity);
  out.effort = borrow<dds_sequence_double>(message.effort);
  out.torque_command = borrow<dds_sequence_double>(message.torque_command);
  copyArray(message.tcp_position, out.tcp_position);
  copyArray(message.tcp_orientation, out.tcp_orientation);
  copyArray(message.tcp_twist, out.tcp_twist);
  toWireStamp(message.reference_stamp, out.reference_stamp);
  out.reference_fields = message.reference_fields;
  copyArray(message.reference_position, out.reference_position);
  copyArray(message.reference_orientation, out.reference_orientation);
  out.reference_joint_position = borrow<dds_sequence_double>(message.reference_joint_position);
  copyArray(message.contact_wrench, out.contact_wrench);
  out.contact_wrench_source = static_cast<std::uint8_t>(message.contact_wrench_source);
  copyArray(message.contact_wrench_tcp, out.contact_wrench_tcp);
  copyArray(message.contact_wrench_task, out.contact_wrench_task);
  out.contact_wrench_bandwidth = message.contact_wrench_bandwidth_hz;
  out.passivity = message.passivity;
  out.tank_energy = message.tank_energy_j;
  out.nullspace_tank_energy = message.nullspace_tank_energy_j;
  out.energy_injected = message.energy_injected_j;
  out.energy_dissipated = message.energy_dissipated_j;
  out.energy_refused = message.energy_refused_j;
  out.gain_fraction = message.gain_fraction;
  return dds_write(writer, &out);
}

template <>
void Wire<ControllerStateMessage>::read(const void* sample, ControllerStateMessage& message,
                                        std::string& /*malformed*/) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__ControllerState_*>(sample);
  headerFromWire(in.header, message.header);
  message.state = static_cast<HostState>(in.state);
  message.command_kind = static_cast<WireCommandKind>(in.command_kind);
  message.cycle = in.cycle;
  message.joint_names.clear();
  for (std::uint32_t i = 0; i < in.joint_names._length; ++i) {
    message.joint_names.push_back(text(in.joint_names._buffer[i]));
  }
  message.position = copyOf<double>(in.position);
  message.velocity = copyOf<double>(in.velocity);
  message.effort = copyOf<double>(in.effort);
  message.torque_command = copyOf<double>(in.torque_command);
  copyArray(in.tcp_position, message.tcp_position);
  copyArray(in.tcp_orientation, message.tcp_orientation);
  copyArray(in.tcp_twist, message.tcp_twist);
  message.reference_stamp = fromWireStamp(in.reference_stamp.sec, in.reference_stamp.nanosec);
  message.reference_fields = in.reference_fields;
  copyArray(in.reference_position, message.reference_position);
  copyArray(in.reference_orientation, message.reference_orientation);
  message.reference_joint_position = copyOf<double>(in.reference_joint_position);
  copyArray(in.contact_wrench, message.contact_wrench);
  message.contact_wrench_source = static_cast<WrenchSource>(in.contact_wrench_source);
  copyArray(in.contact_wrench_tcp, message.contact_wrench_tcp);
  copyArray(in.contact_wrench_task, message.contact_wrench_task);
  message.contact_wrench_bandwidth_hz = in.contact_wrench_bandwidth;
  message.passivity = in.passivity;
  message.tank_energy_j = in.tank_energy;
  message.nullspace_tank_energy_j = in.nullspace_tank_energy;
  message.energy_injected_j = in.energy_injected;
  message.energy_dissipated_j = in.energy_dissipated;
  message.energy_refused_j = in.energy_refused;
  message.gain_fraction = in.gain_fraction;
}

template <>
const dds_topic_descriptor_t* Wire<DiagnosticsMessage>::descriptor() {
  return &comply_msgs_msg_dds__Diagnostics__desc;
}

namespace {

comply_msgs_msg_dds__CommandOutcome_ outcomeToWire(const CommandOutcomeMessage& outcome) {
  comply_msgs_msg_dds__CommandOutcome_ out{};
  toWireStamp(outcome.stamp, out.stamp);
  out.command_kind = static_cast<std::uint8_t>(outcome.command_kind);
  out.outcome = static_cast<std::uint8_t>(outcome.outcome);
  out.reason = static_cast<std::uint8_t>(outcome.reason);
  out.cycle = outcome.cycle;
  toWireStamp(outcome.received, out.received);
  toWireStamp(outcome.applied, out.applied);
  out.message = const_cast<char*>(outcome.message.c_str());
  std::copy(outcome.sender.begin(), outcome.sender.end(), std::begin(out.sender));
  return out;
}

CommandOutcomeMessage outcomeFromWire(const comply_msgs_msg_dds__CommandOutcome_& in) {
  CommandOutcomeMessage outcome;
  outcome.stamp = fromWireStamp(in.stamp.sec, in.stamp.nanosec);
  outcome.command_kind = static_cast<WireCommandKind>(in.command_kind);
  outcome.outcome = static_cast<Outcome>(in.outcome);
  outcome.reason = static_cast<Reason>(in.reason);
  outcome.cycle = in.cycle;
  outcome.received = fromWireStamp(in.received.sec, in.received.nanosec);
  outcome.applied = fromWireStamp(in.applied.sec, in.applied.nanosec);
  outcome.message = text(in.message);
  std::copy(std::begin(in.sender), std::end(in.sender), outcome.sender.begin());
  return outcome;
}

}  // namespace

template <>
dds_return_t Wire<DiagnosticsMessage>::write(dds_entity_t writer,
                                             const DiagnosticsMessage& message) {
  comply_msgs_msg_dds__Diagnostics_ out{};
  headerToWire(message.header, out.header);
  out.state = static_cast<std::uint8_t>(message.state);
  out.cycles = message.cycles;
  out.overruns = message.overruns;
  out.period = message.period_s;
  out.commands_received = message.commands_received;
  out.commands_applied = message.commands_applied;
  out.commands_rejected = message.commands_rejected;
  out.rejections = borrow<dds_sequence_unsigned_long_long>(message.rejections);
  out.watchdog_timeouts = message.watchdog_timeouts;
  out.faults = message.faults;
  out.rate_limit_hits = message.rate_limit_hits;
  out.effort_limit_hits = message.effort_limit_hits;
  out.histogram_bin = message.histogram_bin_s;
  out.compute_time_histogram =
      borrow<dds_sequence_unsigned_long_long>(message.compute_time_histogram);
  out.start_lateness_histogram =
      borrow<dds_sequence_unsigned_long_long>(message.start_lateness_histogram);
  out.last_fault = const_cast<char*>(message.last_fault.c_str());
  out.last_rejection = const_cast<char*>(message.last_rejection.c_str());
  out.publisher = const_cast<char*>(message.publisher.c_str());
  out.records_dropped = message.records_dropped;
  out.recording = const_cast<char*>(message.recording.c_str());
  std::vector<comply_msgs_msg_dds__CommandOutcome_> outcomes;
  outcomes.reserve(message.outcomes.size());
  for (const CommandOutcomeMessage& outcome : message.outcomes) {
    outcomes.push_back(outcomeToWire(outcome));
  }
  out.outcomes = borrow<dds_sequence_comply_msgs_msg_dds__CommandOutcome_>(outcomes);
  return dds_write(writer, &out);
}

template <>
void Wire<DiagnosticsMessage>::read(const void* sample, DiagnosticsMessage& message,
                                    std::string& /*malformed*/) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Diagnostics_*>(sample);
  headerFromWire(in.header, message.header);
  message.state = static_cast<HostState>(in.state);
  message.cycles = in.cycles;
  message.overruns = in.overruns;
  message.period_s = in.period;
  message.commands_received = in.commands_received;
  message.commands_applied = in.commands_applied;
  message.commands_rejected = in.commands_rejected;
  message.rejections = copyOf<std::uint64_t>(in.rejections);
  message.watchdog_timeouts = in.watchdog_timeouts;
  message.faults = in.faults;
  message.rate_limit_hits = in.rate_limit_hits;
  message.effort_limit_hits = in.effort_limit_hits;
  message.histogram_bin_s = in.histogram_bin;
  message.compute_time_histogram = copyOf<std::uint64_t>(in.compute_time_histogram);
  message.start_lateness_histogram = copyOf<std::uint64_t>(in.start_lateness_histogram);
  message.last_fault = text(in.last_fault);
  message.last_rejection = text(in.last_rejection);
  message.publisher = text(in.publisher);
  message.records_dropped = in.records_dropped;
  message.recording = text(in.recording);
  message.outcomes.clear();
  for (std::uint32_t i = 0; i < in.outcomes._length; ++i) {
    message.outcomes.push_back(outcomeFromWire(in.outcomes._buffer[i]));
  }
}

template <>
const dds_topic_descriptor_t* Wire<RequestMessage>::descriptor() {
  return &comply_msgs_msg_dds__Request__desc;
}

template <>
dds_return_t Wire<RequestMessage>::write(dds_entity_t writer, const RequestMessage& message) {
  comply_msgs_msg_dds__Request_ out{};
  headerToWire(message.header, out.header);
  out.request = static_cast<std::uint8_t>(message.request);
  return dds_write(writer, &out);
}

template <>
void Wire<RequestMessage>::read(const void* sample, RequestMessage& message,
                                std::string& malformed) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Request_*>(sample);
  headerFromWire(in.header, message.header);
  message.request = static_cast<RequestType>(in.request);
  if (in.request < static_cast<std::uint8_t>(RequestType::kActivate) ||
      in.request > static_cast<std::uint8_t>(RequestType::kTare)) {
    malformed = "request " + std::to_string(in.request) + " is none of REQUEST_* (1 to 4)";
  }
}

}  // namespace comply::transport::wire
