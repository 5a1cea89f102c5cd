// The live messages back from their CDR bytes, field by field in the order cdr_messages.cpp
// writes them (the commands from the schema tables, the host's messages from theirs). What the
// transport process and the host hand each other (process/frame_adapter.cpp); tests/transport
// holds every decoder against its encoder and against the bytes CycloneDDS puts on the wire.

#include <Eigen/Core>

#include "cdr_fields.hpp"
#include "cdr_reader.hpp"
#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"
#include "comply/transport/cdr.hpp"

namespace comply::transport {
namespace {

using cdr::Reader;
using schema::FieldKind;

// The fewest bytes one element of each sequence takes: a bound on a count before reading it.
constexpr std::size_t kStringBytes = 5;  // length and NUL
constexpr std::size_t kHeaderBytes = 8 + kStringBytes;

Stamp getStamp(Reader& r) {
  Stamp stamp;
  stamp.sec = r.get<std::int32_t>();
  stamp.nanosec = r.get<std::uint32_t>();
  return stamp;
}

Header getHeader(Reader& r) {
  Header header;
  header.stamp = getStamp(r);
  header.frame_id = r.getString();
  return header;
}

template <typename Enum>
Enum getEnum(Reader& r) {
  return static_cast<Enum>(r.get<std::uint8_t>());
}

template <FieldKind K, typename Value>
void getField(Reader& r, Value& value) {
  if constexpr (K == FieldKind::kQuaternion) {
    double xyzw[4] = {};
    r.getArray(xyzw, 4);
    value = schema::fromXyzw(xyzw);
  } else if constexpr (K == FieldKind::kBlock3) {
    double row_major[9] = {};
    r.getArray(row_major, 9);
    value = schema::fromRowMajor(row_major);
  } else if constexpr (K == FieldKind::kEnum) {
    value = getEnum<Value>(r);
  } else if constexpr (K == FieldKind::kJointVector) {
    value.resize(static_cast<Eigen::Index>(r.getCount(sizeof(double), kMaxDof)));
    r.getArray(value.data(), static_cast<std::size_t>(value.size()));
  } else {
    r.getArray(value.data(), static_cast<std::size_t>(value.size()));
  }
}

#define COMPLY_CDR_GET_FIELD(name, group, kind, type, unit, constraint, role, init, doc) \
  getField<FieldKind::kind>(r, command.name);

void getCommand(Reader& r, CartesianCommand& command) {
  command.fields = static_cast<CommandField>(r.get<std::uint32_t>());
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_CDR_GET_FIELD)
}

void getCommand(Reader& r, JointCommand& command) {
  command.fields = static_cast<CommandField>(r.get<std::uint32_t>());
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_CDR_GET_FIELD)
}

/// A command message: stamp_s from the header, as the DDS reader derives it.
template <typename Message>
void getCommandMessage(Reader& r, Message& message) {
  message.header = getHeader(r);
  message.command.stamp_s = message.header.stamp.seconds();
  getCommand(r, message.command);
}

/// A chunk: each waypoint a command whose header.stamp is its time.
template <typename Message>
void getChunk(Reader& r, Message& message) {
  message.header = getHeader(r);
  message.chunk.stamp_s = message.header.stamp.seconds();
  message.chunk.fields = static_cast<CommandField>(r.get<std::uint32_t>());
  Stamp observation;
  Stamp takeover;
  cdr::getField(r, observation);
  cdr::getField(r, takeover);
  message.chunk.observation_s = secondsOrNaN(observation);
  message.chunk.takeover_s = secondsOrNaN(takeover);
  message.chunk.waypoints.resize(r.getCount(kHeaderBytes + 4, kMaxChunkWaypoints));
  for (auto& waypoint : message.chunk.waypoints) {
    waypoint.time_s = getHeader(r).stamp.seconds();
    getCommand(r, waypoint.command);
  }
}

/// An answer: at most kMaxChunkWaypoints commands in either list, as a chunk's waypoints.
void getCommitted(Reader& r, CommittedMessage& message) {
  message.header = getHeader(r);
  message.request_stamp = getStamp(r);
  cdr::getField(r, message.sender);
  message.command_kind = getEnum<WireCommandKind>(r);
  message.answered = r.getBool();
  message.known = r.getBool();
  message.message = r.getString();
  message.cartesian.resize(r.getCount(kHeaderBytes + 4, kMaxChunkWaypoints));
  for (CartesianCommandMessage& command : message.cartesian) {
    getCommandMessage(r, command);
  }
  message.joint.resize(r.getCount(kHeaderBytes + 4, kMaxChunkWaypoints));
  for (JointCommandMessage& command : message.joint) {
    getCommandMessage(r, command);
  }
}

/// A recorded cycle: the state, its timing, and the command in force (0 or 1 of either kind).
void getCycleRecord(Reader& r, CycleRecordMessage& message) {
  cdr::getFields(r, message.state);
  message.compute_time_s = r.get<double>();
  message.start_lateness_s = r.get<double>();
  message.cartesian_in_force.resize(r.getCount(kHeaderBytes + 4, 1));
  for (CartesianCommandMessage& command : message.cartesian_in_force) {
    getCommandMessage(r, command);
  }
  message.joint_in_force.resize(r.getCount(kHeaderBytes + 4, 1));
  for (JointCommandMessage& command : message.joint_in_force) {
    getCommandMessage(r, command);
  }
}

/// `get` reads the message from the bytes; whether they held one, to their end or not.
template <typename Message, typename Get>
bool decodeWith(std::span<const std::uint8_t> bytes, Message& message, Get get) {
  Reader r(bytes);
  get(r, message);
  return r.ok();
}

}  // namespace

bool decodeCdr(std::span<const std::uint8_t> bytes, ControllerStateMessage& message) {
  return decodeWith(bytes, message, cdr::getFields<ControllerStateMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, DiagnosticsMessage& message) {
  return decodeWith(bytes, message, cdr::getFields<DiagnosticsMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CartesianCommandMessage& message) {
  return decodeWith(bytes, message, getCommandMessage<CartesianCommandMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, JointCommandMessage& message) {
  return decodeWith(bytes, message, getCommandMessage<JointCommandMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CartesianChunkMessage& message) {
  return decodeWith(bytes, message, getChunk<CartesianChunkMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, JointChunkMessage& message) {
  return decodeWith(bytes, message, getChunk<JointChunkMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, RequestMessage& message) {
  Reader r(bytes);
  message.header = getHeader(r);
  message.request = getEnum<RequestType>(r);
  return r.ok();
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CommittedRequestMessage& message) {
  return decodeWith(bytes, message, cdr::getFields<CommittedRequestMessage>);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CommittedMessage& message) {
  return decodeWith(bytes, message, getCommitted);
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CycleRecordMessage& message) {
  return decodeWith(bytes, message, getCycleRecord);
}

}  // namespace comply::transport
