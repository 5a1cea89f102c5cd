// The command and chunk messages on the wire, field by field from the schema tables
// (schema/table.hpp): the generated DDS structs have one member per table row with the same name,
// so a new row needs no code here. A chunk's waypoints are commands, and so are the entries of a
// committed request's answer (Committed).

#include <Eigen/Core>
#include <algorithm>
#include <iterator>
#include <vector>

#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"
#include "comply_msgs/msg/CartesianChunk.h"
#include "comply_msgs/msg/CartesianCommand.h"
#include "comply_msgs/msg/Committed.h"
#include "comply_msgs/msg/JointChunk.h"
#include "comply_msgs/msg/JointCommand.h"
#include "wire.hpp"

namespace comply::transport::wire {
namespace {

using schema::FieldKind;

template <FieldKind K, typename Value, typename WireValue>
void toWire(const Value& value, WireValue& out) {
  if constexpr (K == FieldKind::kQuaternion) {
    schema::toXyzw(value, out);
  } else if constexpr (K == FieldKind::kBlock3) {
    schema::toRowMajor(value, out);
  } else if constexpr (K == FieldKind::kEnum) {
    out = static_cast<std::uint8_t>(value);
  } else if constexpr (K == FieldKind::kJointVector) {
    // Points at the command's own storage: dds_write serialises before returning.
    out._maximum = out._length = static_cast<std::uint32_t>(value.size());
    out._buffer = const_cast<double*>(value.data());
    out._release = false;
  } else {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      out[i] = value[i];
    }
  }
}

template <FieldKind K, typename WireValue, typename Value>
void fromWire(const WireValue& in, Value& value, const char* name, std::string& malformed) {
  if (!malformed.empty()) {
    return;  // the first thing wrong is the one named
  }
  if constexpr (K == FieldKind::kQuaternion) {
    value = schema::fromXyzw(in);
  } else if constexpr (K == FieldKind::kBlock3) {
    value = schema::fromRowMajor(in);
  } else if constexpr (K == FieldKind::kEnum) {
    value = static_cast<Value>(in);
  } else if constexpr (K == FieldKind::kJointVector) {
    if (in._length > static_cast<std::uint32_t>(kMaxDof)) {
      malformed = std::string(name) + " has " + std::to_string(in._length) +
                  " entries, more than any controller's joints (" + std::to_string(kMaxDof) + ")";
      value.resize(0);
      return;
    }
    value = Eigen::Map<const Eigen::VectorXd>(in._buffer, in._length);
  } else {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      value[i] = in[i];
    }
  }
}

template <typename WireHeader>
void headerToWire(const Header& header, WireHeader& out) {
  toWireStamp(header.stamp, out.stamp);
  out.frame_id = const_cast<char*>(header.frame_id.c_str());
}

#define COMPLY_WIRE_TO(name, group, kind, type, unit, constraint, role, init, doc) \
  toWire<FieldKind::kind>(command.name, out.name);
#define COMPLY_WIRE_FROM(name, group, kind, type, unit, constraint, role, init, doc) \
  fromWire<FieldKind::kind>(in.name, command.name, #name, malformed);

using WireCartesian = comply_msgs_msg_dds__CartesianCommand_;
using WireJoint = comply_msgs_msg_dds__JointCommand_;

/// One command's fields (not its header); the wire value points into `command` where it can.
void commandToWire(const CartesianCommand& command, WireCartesian& out) {
  out.fields = static_cast<std::uint32_t>(command.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_WIRE_TO)
}
void commandToWire(const JointCommand& command, WireJoint& out) {
  out.fields = static_cast<std::uint32_t>(command.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_WIRE_TO)
}
/// `malformed`: the first field no command may hold (a joint vector longer than kMaxDof).
void commandFromWire(const WireCartesian& in, CartesianCommand& command, std::string& malformed) {
  command.fields = static_cast<CommandField>(in.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_WIRE_FROM)
}
void commandFromWire(const WireJoint& in, JointCommand& command, std::string& malformed) {
  command.fields = static_cast<CommandField>(in.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_WIRE_FROM)
}

template <typename WireCommand, typename Message>
dds_return_t writeCommand(dds_entity_t writer, const Message& message) {
  WireCommand out{};
  headerToWire(message.header, out.header);
  commandToWire(message.command, out);
  return dds_write(writer, &out);
}

template <typename WireCommand, typename Message>
void readCommand(const void* wire, Sample<Message>& sample) {
  const auto& in = *static_cast<const WireCommand*>(wire);
  Message& message = sample.message;
  message.header = headerFromWire(in.header, sample);
  message.command.stamp_s = message.header.stamp.seconds();
  std::string malformed;
  commandFromWire(in, message.command, malformed);
  if (!malformed.empty()) {
    sample.refuse(Reason::kDofMismatch, malformed);
  }
}

/// A chunk: each waypoint a command whose header.stamp is its time.
template <typename WireChunk, typename WireCommand, typename Message>
dds_return_t writeChunk(dds_entity_t writer, const Message& message) {
  const auto& waypoints = message.chunk.waypoints;
  std::vector<WireCommand> wire_waypoints(waypoints.size());
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    toWireStamp(Stamp::fromSeconds(waypoints[k].time_s), wire_waypoints[k].header.stamp);
    wire_waypoints[k].header.frame_id = const_cast<char*>(message.header.frame_id.c_str());
    commandToWire(waypoints[k].command, wire_waypoints[k]);
    wire_waypoints[k].fields = static_cast<std::uint32_t>(message.chunk.fields);
  }
  WireChunk out{};
  headerToWire(message.header, out.header);
  out.fields = static_cast<std::uint32_t>(message.chunk.fields);
  toWireStamp(stampOrZero(message.chunk.observation_s), out.observation);
  toWireStamp(stampOrZero(message.chunk.takeover_s), out.takeover);
  out.waypoints._maximum = out.waypoints._length = static_cast<std::uint32_t>(waypoints.size());
  out.waypoints._buffer = wire_waypoints.data();
  out.waypoints._release = false;
  return dds_write(writer, &out);
}

/// The wire does not bound the waypoints (a bound there made DDS drop a longer chunk unanswered):
/// a chunk of more than kMaxChunkWaypoints is refused here, as validation words it, none of its
/// waypoints read.
template <typename WireChunk, typename Message>
void readChunk(const void* wire, Sample<Message>& sample) {
  const auto& in = *static_cast<const WireChunk*>(wire);
  Message& message = sample.message;
  message.header = headerFromWire(in.header, sample);
  message.chunk.stamp_s = message.header.stamp.seconds();
  message.chunk.fields = static_cast<CommandField>(in.fields);
  message.chunk.observation_s =
      secondsOrNaN(fromWireStamp(in.observation.sec, in.observation.nanosec));
  message.chunk.takeover_s = secondsOrNaN(fromWireStamp(in.takeover.sec, in.takeover.nanosec));
  if (in.waypoints._length > static_cast<std::uint32_t>(kMaxChunkWaypoints)) {
    sample.refuse(Reason::kInvalidChunk,
                  "a chunk carries 1 to " + std::to_string(kMaxChunkWaypoints) +
                      " waypoints, this one " + std::to_string(in.waypoints._length));
    return;
  }
  message.chunk.waypoints.resize(in.waypoints._length);
  for (std::uint32_t k = 0; k < in.waypoints._length; ++k) {
    const auto& waypoint_in = in.waypoints._buffer[k];
    auto& waypoint = message.chunk.waypoints[k];
    const std::string where = "waypoint " + std::to_string(k) + ": ";
    waypoint.time_s = headerFromWire(waypoint_in.header, sample, where).stamp.seconds();
    std::string malformed;
    commandFromWire(waypoint_in, waypoint.command, malformed);
    if (!malformed.empty()) {
      sample.refuse(Reason::kDofMismatch, where + malformed);
    }
    if (!sample.malformed.empty()) {
      return;
    }
  }
}

/// Commands as their wire structs; each points into its command's storage until dds_write.
template <typename WireCommand, typename CommandMessage>
std::vector<WireCommand> commandsToWire(const std::vector<CommandMessage>& commands) {
  std::vector<WireCommand> out(commands.size());
  for (std::size_t k = 0; k < commands.size(); ++k) {
    headerToWire(commands[k].header, out[k].header);
    commandToWire(commands[k].command, out[k]);
  }
  return out;
}

template <typename Sequence, typename WireCommand>
Sequence borrowSequence(std::vector<WireCommand>& values) {
  Sequence sequence{};
  sequence._maximum = sequence._length = static_cast<std::uint32_t>(values.size());
  sequence._buffer = values.data();
  sequence._release = false;
  return sequence;
}

dds_return_t writeCommitted(dds_entity_t writer, const CommittedMessage& message) {
  std::vector<WireCartesian> cartesian = commandsToWire<WireCartesian>(message.cartesian);
  std::vector<WireJoint> joint = commandsToWire<WireJoint>(message.joint);
  comply_msgs_msg_dds__Committed_ out{};
  headerToWire(message.header, out.header);
  toWireStamp(message.request_stamp, out.request_stamp);
  std::copy(message.sender.begin(), message.sender.end(), out.sender);
  out.command_kind = static_cast<std::uint8_t>(message.command_kind);
  out.answered = message.answered;
  out.known = message.known;
  out.message = const_cast<char*>(message.message.c_str());
  out.cartesian = borrowSequence<dds_sequence_comply_msgs_msg_dds__CartesianCommand_>(cartesian);
  out.joint = borrowSequence<dds_sequence_comply_msgs_msg_dds__JointCommand_>(joint);
  return dds_write(writer, &out);
}

/// One list of an answer, at most kMaxChunkWaypoints commands (as a chunk's waypoints); `name`
/// names it in the refusal.
template <typename Sequence, typename CommandMessage>
void commandsFromWire(const Sequence& in, std::vector<CommandMessage>& out, const char* name,
                      Sample<CommittedMessage>& sample) {
  if (in._length > static_cast<std::uint32_t>(kMaxChunkWaypoints)) {
    sample.refuse(Reason::kInvalidChunk, std::string(name) + " has " + std::to_string(in._length) +
                                             " entries, more than an answer holds (" +
                                             std::to_string(kMaxChunkWaypoints) + ")");
    return;
  }
  out.resize(in._length);
  for (std::uint32_t k = 0; k < in._length && sample.malformed.empty(); ++k) {
    const std::string where = std::string(name) + "[" + std::to_string(k) + "]: ";
    out[k].header = headerFromWire(in._buffer[k].header, sample, where);
    out[k].command.stamp_s = out[k].header.stamp.seconds();
    std::string malformed;
    commandFromWire(in._buffer[k], out[k].command, malformed);
    if (!malformed.empty()) {
      sample.refuse(Reason::kDofMismatch, where + malformed);
    }
  }
}

void readCommitted(const void* wire, Sample<CommittedMessage>& sample) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Committed_*>(wire);
  CommittedMessage& message = sample.message;
  message.header = headerFromWire(in.header, sample);
  message.request_stamp = fromWireStamp(in.request_stamp.sec, in.request_stamp.nanosec);
  std::copy(std::begin(in.sender), std::end(in.sender), message.sender.begin());
  message.command_kind = static_cast<WireCommandKind>(in.command_kind);
  message.answered = in.answered;
  message.known = in.known;
  message.message = in.message != nullptr ? in.message : "";
  commandsFromWire(in.cartesian, message.cartesian, "cartesian", sample);
  commandsFromWire(in.joint, message.joint, "joint", sample);
}

}  // namespace

COMPLY_WIRE_MESSAGE(CartesianCommandMessage, comply_msgs_msg_dds__CartesianCommand__desc,
                    writeCommand<WireCartesian>, readCommand<WireCartesian>)
COMPLY_WIRE_MESSAGE(JointCommandMessage, comply_msgs_msg_dds__JointCommand__desc,
                    writeCommand<WireJoint>, readCommand<WireJoint>)
COMPLY_WIRE_MESSAGE(CartesianChunkMessage, comply_msgs_msg_dds__CartesianChunk__desc,
                    (writeChunk<comply_msgs_msg_dds__CartesianChunk_, WireCartesian>),
                    readChunk<comply_msgs_msg_dds__CartesianChunk_>)
COMPLY_WIRE_MESSAGE(JointChunkMessage, comply_msgs_msg_dds__JointChunk__desc,
                    (writeChunk<comply_msgs_msg_dds__JointChunk_, WireJoint>),
                    readChunk<comply_msgs_msg_dds__JointChunk_>)

COMPLY_WIRE_MESSAGE(CommittedMessage, comply_msgs_msg_dds__Committed__desc, writeCommitted,
                    readCommitted)

}  // namespace comply::transport::wire
