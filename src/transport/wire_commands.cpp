// The command messages on the wire, field by field from the schema tables (schema/table.hpp):
// the generated DDS structs have one member per table row with the same name, so a new row
// needs no code here.

#include <Eigen/Core>

#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"
#include "comply_msgs/msg/CartesianCommand.h"
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
    for (int k = 0; k < 9; ++k) {
      out[k] = value(k / 3, k % 3);
    }
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
  if constexpr (K == FieldKind::kQuaternion) {
    value = schema::fromXyzw(in);
  } else if constexpr (K == FieldKind::kBlock3) {
    for (int k = 0; k < 9; ++k) {
      value(k / 3, k % 3) = in[k];
    }
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

template <typename WireHeader>
void headerFromWire(const WireHeader& in, Header& header) {
  header.stamp = fromWireStamp(in.stamp.sec, in.stamp.nanosec);
  header.frame_id = in.frame_id != nullptr ? in.frame_id : "";
}

#define COMPLY_WIRE_TO(name, group, kind, type, unit, constraint, role, init, doc) \
  toWire<FieldKind::kind>(message.command.name, out.name);
#define COMPLY_WIRE_FROM(name, group, kind, type, unit, constraint, role, init, doc) \
  fromWire<FieldKind::kind>(in.name, message.command.name, #name, malformed);

}  // namespace

template <>
const dds_topic_descriptor_t* Wire<CartesianCommandMessage>::descriptor() {
  return &comply_msgs_msg_dds__CartesianCommand__desc;
}

template <>
dds_return_t Wire<CartesianCommandMessage>::write(dds_entity_t writer,
                                                  const CartesianCommandMessage& message) {
  comply_msgs_msg_dds__CartesianCommand_ out{};
  headerToWire(message.header, out.header);
  out.fields = static_cast<std::uint32_t>(message.command.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_WIRE_TO)
  return dds_write(writer, &out);
}

template <>
void Wire<CartesianCommandMessage>::read(const void* sample, CartesianCommandMessage& message,
                                         std::string& malformed) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__CartesianCommand_*>(sample);
  headerFromWire(in.header, message.header);
  message.command.stamp_s = message.header.stamp.seconds();
  message.command.fields = static_cast<CommandField>(in.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_WIRE_FROM)
}

template <>
const dds_topic_descriptor_t* Wire<JointCommandMessage>::descriptor() {
  return &comply_msgs_msg_dds__JointCommand__desc;
}

template <>
dds_return_t Wire<JointCommandMessage>::write(dds_entity_t writer,
                                              const JointCommandMessage& message) {
  comply_msgs_msg_dds__JointCommand_ out{};
  headerToWire(message.header, out.header);
  out.fields = static_cast<std::uint32_t>(message.command.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_WIRE_TO)
  return dds_write(writer, &out);
}

template <>
void Wire<JointCommandMessage>::read(const void* sample, JointCommandMessage& message,
                                     std::string& malformed) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__JointCommand_*>(sample);
  headerFromWire(in.header, message.header);
  message.command.stamp_s = message.header.stamp.seconds();
  message.command.fields = static_cast<CommandField>(in.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_WIRE_FROM)
}

}  // namespace comply::transport::wire
