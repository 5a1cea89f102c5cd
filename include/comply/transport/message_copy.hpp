#pragma once
// The host's messages copied, by their tables, into another middleware's types of the same .msg
// files: ROS 2's comply_msgs (the ros2_control controllers), or any struct whose members carry the
// fields' wire names. A row added to a table reaches such a copy without a line written here.
//
// The target's members: the wire name of each row; numbers and enums as any arithmetic type;
// strings as std::string; fixed arrays as anything indexable; sequences with resize() and
// operator[]; builtin_interfaces/Time with sec and nanosec; std_msgs/Header with stamp and
// frame_id; a nested message (Diagnostics' outcomes, an outcome's chunk) as that message's own
// target type.

#include <array>
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

namespace message_copy {

template <typename Out>
void copyField(const Stamp& in, Out& out) {
  out.sec = in.sec;
  out.nanosec = in.nanosec;
}

template <typename Out>
void copyField(const Header& in, Out& out) {
  copyField(in.stamp, out.stamp);
  out.frame_id = in.frame_id;
}

template <typename Out>
void copyField(const std::string& in, Out& out) {
  out = in;
}

template <typename In, typename Out>
requires std::is_arithmetic_v<In> || std::is_enum_v<In>
void copyField(const In& in, Out& out) {
  out = static_cast<Out>(in);
}

template <typename In, std::size_t N, typename Out>
void copyField(const std::array<In, N>& in, Out& out) {
  for (std::size_t i = 0; i < N; ++i) {
    copyField(in[i], out[i]);
  }
}

/// A nested message: its copyMessage, found next to its struct.
template <TableMessage In, typename Out>
void copyField(const In& in, Out& out) {
  copyMessage(in, out);
}

template <typename In, typename Out>
void copyField(const std::vector<In>& in, Out& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    copyField(in[i], out[i]);
  }
}

}  // namespace message_copy

/// copyMessage(in, out) for a message struct declared from TABLE (COMPLY_MESSAGE_BODY).
#define COMPLY_MESSAGE_COPY_FIELD(Type, member, wire, init, doc) \
  ::comply::transport::message_copy::copyField(in.member, out.wire);
#define COMPLY_MESSAGE_COPY(Message, TABLE)       \
  template <typename Out>                         \
  void copyMessage(const Message& in, Out& out) { \
    TABLE(COMPLY_MESSAGE_COPY_FIELD)              \
  }

COMPLY_MESSAGE_COPY(ControllerStateMessage, COMPLY_CONTROLLER_STATE_FIELDS)
COMPLY_MESSAGE_COPY(ChunkTimingMessage, COMPLY_CHUNK_TIMING_FIELDS)
COMPLY_MESSAGE_COPY(CommandOutcomeMessage, COMPLY_COMMAND_OUTCOME_FIELDS)
COMPLY_MESSAGE_COPY(DiagnosticsMessage, COMPLY_DIAGNOSTICS_FIELDS)

}  // namespace comply::transport
