// ControllerState, Diagnostics and Request on the wire. The first two member by member from
// their tables (message_tables.hpp, wire_fields.hpp).

#include "comply_msgs/msg/ControllerState.h"
#include "comply_msgs/msg/Request.h"
#include "wire.hpp"
#include "wire_fields.hpp"

namespace comply::transport::wire {

template <>
const dds_topic_descriptor_t* Wire<ControllerStateMessage>::descriptor() {
  return &comply_msgs_msg_dds__ControllerState__desc;
}

template <>
dds_return_t Wire<ControllerStateMessage>::write(dds_entity_t writer,
                                                 const ControllerStateMessage& message) {
  comply_msgs_msg_dds__ControllerState_ out{};
  Borrowed borrowed;
  COMPLY_CONTROLLER_STATE_FIELDS(COMPLY_TO_WIRE)
  return dds_write(writer, &out);
}

template <>
void Wire<ControllerStateMessage>::read(const void* sample, ControllerStateMessage& message,
                                        std::string& /*malformed*/) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__ControllerState_*>(sample);
  COMPLY_CONTROLLER_STATE_FIELDS(COMPLY_FROM_WIRE)
}

template <>
const dds_topic_descriptor_t* Wire<DiagnosticsMessage>::descriptor() {
  return &comply_msgs_msg_dds__Diagnostics__desc;
}

template <>
dds_return_t Wire<DiagnosticsMessage>::write(dds_entity_t writer,
                                             const DiagnosticsMessage& message) {
  comply_msgs_msg_dds__Diagnostics_ out{};
  Borrowed borrowed;
  COMPLY_DIAGNOSTICS_FIELDS(COMPLY_TO_WIRE)
  return dds_write(writer, &out);
}

template <>
void Wire<DiagnosticsMessage>::read(const void* sample, DiagnosticsMessage& message,
                                    std::string& /*malformed*/) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Diagnostics_*>(sample);
  COMPLY_DIAGNOSTICS_FIELDS(COMPLY_FROM_WIRE)
}

template <>
const dds_topic_descriptor_t* Wire<RequestMessage>::descriptor() {
  return &comply_msgs_msg_dds__Request__desc;
}

template <>
dds_return_t Wire<RequestMessage>::write(dds_entity_t writer, const RequestMessage& message) {
  comply_msgs_msg_dds__Request_ out{};
  Borrowed borrowed;
  toWire(message.header, out.header, borrowed);
  out.request = static_cast<std::uint8_t>(message.request);
  return dds_write(writer, &out);
}

template <>
void Wire<RequestMessage>::read(const void* sample, RequestMessage& message,
                                std::string& malformed) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Request_*>(sample);
  fromWire(in.header, message.header);
  message.request = static_cast<RequestType>(in.request);
  if (in.request < static_cast<std::uint8_t>(RequestType::kActivate) ||
      in.request > static_cast<std::uint8_t>(RequestType::kTare)) {
    malformed = "request " + std::to_string(in.request) + " is none of REQUEST_* (1 to 4)";
  }
}

}  // namespace comply::transport::wire
