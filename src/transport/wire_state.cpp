// ControllerState, Diagnostics, Request and CommittedRequest on the wire. The first two member by
// member from their tables (message_tables.hpp, wire_fields.hpp), a committed request too but for
// its header.

#include <type_traits>

#include "comply_msgs/msg/CommittedRequest.h"
#include "comply_msgs/msg/ControllerState.h"
#include "comply_msgs/msg/Request.h"
#include "wire.hpp"
#include "wire_fields.hpp"

namespace comply::transport::wire {

/// A message of the tables, member by member: write and read through the table TABLE.
#define COMPLY_WIRE_TABLE_MESSAGE(Message, Dds, TABLE)                       \
  namespace {                                                                \
  dds_return_t write##Message(dds_entity_t writer, const Message& message) { \
    Dds out{};                                                               \
    Borrowed borrowed;                                                       \
    TABLE(COMPLY_TO_WIRE)                                                    \
    return dds_write(writer, &out);                                          \
  }                                                                          \
  void read##Message(const void* wire, Sample<Message>& sample) {            \
    const auto& in = *static_cast<const Dds*>(wire);                         \
    Message& message = sample.message;                                       \
    TABLE(COMPLY_FROM_WIRE)                                                  \
  }                                                                          \
  }                                                                          \
  COMPLY_WIRE_MESSAGE(Message, Dds##_desc, write##Message, read##Message)

COMPLY_WIRE_TABLE_MESSAGE(ControllerStateMessage, comply_msgs_msg_dds__ControllerState_,
                          COMPLY_CONTROLLER_STATE_FIELDS)
COMPLY_WIRE_TABLE_MESSAGE(DiagnosticsMessage, comply_msgs_msg_dds__Diagnostics_,
                          COMPLY_DIAGNOSTICS_FIELDS)

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
void Wire<RequestMessage>::read(const void* wire, Sample<RequestMessage>& sample) {
  const auto& in = *static_cast<const comply_msgs_msg_dds__Request_*>(wire);
  RequestMessage& message = sample.message;
  message.header = headerFromWire(in.header, sample);
  message.request = static_cast<RequestType>(in.request);
  if (nameIn(kRequestTypeNames, message.request, "").empty()) {
    sample.refuse(Reason::kOutOfRange,
                  "request " + std::to_string(in.request) + " is none of REQUEST_*");
  }
}

using WireCommittedRequest = comply_msgs_msg_dds__CommittedRequest_;

template <>
const dds_topic_descriptor_t* Wire<CommittedRequestMessage>::descriptor() {
  return &comply_msgs_msg_dds__CommittedRequest__desc;
}

template <>
dds_return_t Wire<CommittedRequestMessage>::write(dds_entity_t writer,
                                                  const CommittedRequestMessage& message) {
  WireCommittedRequest out{};
  Borrowed borrowed;
  COMPLY_COMMITTED_REQUEST_FIELDS(COMPLY_TO_WIRE)
  return dds_write(writer, &out);
}

/// Every row from the table but the header, which is read as every request's: a frame_id over
/// its bound refuses the request (it is answered with why) and is not copied.
#define COMPLY_FROM_WIRE_BUT_HEADER(Type, member, wire, init, doc) \
  if constexpr (!std::is_same_v<Type, Header>) {                   \
    fromWire(in.wire, message.member);                             \
  }

template <>
void Wire<CommittedRequestMessage>::read(const void* wire,
                                         Sample<CommittedRequestMessage>& sample) {
  const auto& in = *static_cast<const WireCommittedRequest*>(wire);
  CommittedRequestMessage& message = sample.message;
  message.header = headerFromWire(in.header, sample);
  COMPLY_COMMITTED_REQUEST_FIELDS(COMPLY_FROM_WIRE_BUT_HEADER)
}

}  // namespace comply::transport::wire
