// The live messages as CDR, field by field in the order of their .msg files (msg/): the commands
// from the schema tables, the host's messages from theirs (cdr_fields.hpp). tests/transport checks
// every message against the bytes CycloneDDS puts on the wire.

#include <Eigen/Core>

#include "cdr_fields.hpp"
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

template <FieldKind K, typename Value>
void putField(Writer& w, const Value& value) {
  if constexpr (K == FieldKind::kQuaternion) {
    double xyzw[4];
    schema::toXyzw(value, xyzw);
    w.putArray(xyzw, 4);
  } else if constexpr (K == FieldKind::kBlock3) {
    double row_major[9];
    schema::toRowMajor(value, row_major);
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
  cdr::putField(w, stampOrZero(message.chunk.observation_s));
  cdr::putField(w, stampOrZero(message.chunk.takeover_s));
  w.putCount(message.chunk.waypoints.size());
  CommandMessage waypoint{{Stamp{}, message.header.frame_id}, Command{}};
  for (const ChunkWaypoint<Command>& from : message.chunk.waypoints) {
    waypoint.header.stamp = Stamp::fromSeconds(from.time_s);
    waypoint.command = from.command;
    waypoint.command.fields = message.chunk.fields;
    put(w, waypoint);
  }
}

void putCartesianChunk(Writer& w, const CartesianChunkMessage& message) {
  putChunk<CartesianCommand, CartesianCommandMessage>(w, message, putCartesian);
}

void putJointChunk(Writer& w, const JointChunkMessage& message) {
  putChunk<JointCommand, JointCommandMessage>(w, message, putJoint);
}

void putRequest(Writer& w, const RequestMessage& message) {
  putHeader(w, message.header);
  w.put(static_cast<std::uint8_t>(message.request));
}

void putCycleRecord(Writer& w, const CycleRecordMessage& message) {
  cdr::putFields(w, message.state);
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
}

/// An answer: the commands of the controller's kind, each a command message stamped with its time.
void putCommitted(Writer& w, const CommittedMessage& message) {
  putHeader(w, message.header);
  putStamp(w, message.request_stamp);
  cdr::putField(w, message.sender);
  w.put(static_cast<std::uint8_t>(message.command_kind));
  w.putBool(message.answered);
  w.putBool(message.known);
  w.putString(message.message);
  w.putCount(message.cartesian.size());
  for (const CartesianCommandMessage& command : message.cartesian) {
    putCartesian(w, command);
  }
  w.putCount(message.joint.size());
  for (const JointCommandMessage& command : message.joint) {
    putJoint(w, command);
  }
}

}  // namespace

#define COMPLY_ENCODE_CDR(Message, PUT)                                    \
  void encodeCdr(const Message& message, std::vector<std::uint8_t>& out) { \
    Writer w(out);                                                         \
    PUT(w, message);                                                       \
    w.finish();                                                            \
  }
COMPLY_ENCODE_CDR(ControllerStateMessage, cdr::putFields)
COMPLY_ENCODE_CDR(CommandOutcomeMessage, cdr::putFields)
COMPLY_ENCODE_CDR(ChunkTimingMessage, cdr::putFields)
COMPLY_ENCODE_CDR(DiagnosticsMessage, cdr::putFields)
COMPLY_ENCODE_CDR(CartesianCommandMessage, putCartesian)
COMPLY_ENCODE_CDR(JointCommandMessage, putJoint)
COMPLY_ENCODE_CDR(CartesianChunkMessage, putCartesianChunk)
COMPLY_ENCODE_CDR(JointChunkMessage, putJointChunk)
COMPLY_ENCODE_CDR(RequestMessage, putRequest)
COMPLY_ENCODE_CDR(CycleRecordMessage, putCycleRecord)
COMPLY_ENCODE_CDR(CommittedRequestMessage, cdr::putFields)
COMPLY_ENCODE_CDR(CommittedMessage, putCommitted)
#undef COMPLY_ENCODE_CDR

#define COMPLY_ROS_TYPE_NAME(Message, name) \
  template <>                               \
  std::string_view rosTypeName<Message>() { \
    return "comply_msgs/msg/" name;         \
  }
COMPLY_ROS_TYPE_NAME(ControllerStateMessage, "ControllerState")
COMPLY_ROS_TYPE_NAME(CommandOutcomeMessage, "CommandOutcome")
COMPLY_ROS_TYPE_NAME(ChunkTimingMessage, "ChunkTiming")
COMPLY_ROS_TYPE_NAME(DiagnosticsMessage, "Diagnostics")
COMPLY_ROS_TYPE_NAME(CartesianCommandMessage, "CartesianCommand")
COMPLY_ROS_TYPE_NAME(JointCommandMessage, "JointCommand")
COMPLY_ROS_TYPE_NAME(CartesianChunkMessage, "CartesianChunk")
COMPLY_ROS_TYPE_NAME(JointChunkMessage, "JointChunk")
COMPLY_ROS_TYPE_NAME(RequestMessage, "Request")
COMPLY_ROS_TYPE_NAME(CycleRecordMessage, "CycleRecord")
COMPLY_ROS_TYPE_NAME(CommittedRequestMessage, "CommittedRequest")
COMPLY_ROS_TYPE_NAME(CommittedMessage, "Committed")
#undef COMPLY_ROS_TYPE_NAME

}  // namespace comply::transport
