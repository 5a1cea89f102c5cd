#pragma once
// A message table's fields to and from the structs idlc generates (message_tables.hpp): a row's
// member becomes the idlc struct's member of the row's wire name, converted by its C++ type.
// COMPLY_TO_WIRE needs `message`, `out` and `borrowed` in scope; COMPLY_FROM_WIRE `in` and
// `message`.

#include <algorithm>
#include <deque>
#include <iterator>
#include <type_traits>
#include <vector>

#include "comply/transport/messages.hpp"
#include "comply_msgs/msg/ControllerState.h"
#include "comply_msgs/msg/Diagnostics.h"
#include "wire.hpp"

namespace comply::transport::wire {

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

inline std::string text(const char* value) {
  return value != nullptr ? value : "";
}

using WireOutcome = comply_msgs_msg_dds__CommandOutcome_;
using WireChunkTiming = comply_msgs_msg_dds__ChunkTiming_;

/// What a message's wire form borrows, alive until dds_write returns.
struct Borrowed {
  std::deque<std::vector<char*>> strings;
  std::deque<std::vector<WireOutcome>> outcomes;
  std::deque<std::vector<WireChunkTiming>> chunk_timings;
};

// ---- to the idlc types ----

template <typename T, typename W>
requires(std::is_arithmetic_v<T> || std::is_enum_v<T>) void toWire(const T& value, W& out,
                                                                   Borrowed& /*borrowed*/) {
  out = static_cast<W>(value);
}
inline void toWire(const std::string& value, char*& out, Borrowed& /*borrowed*/) {
  out = const_cast<char*>(value.c_str());
}
inline void toWire(const Stamp& value, builtin_interfaces_msg_dds__Time_& out,
                   Borrowed& /*borrowed*/) {
  toWireStamp(value, out);
}
inline void toWire(const Header& value, std_msgs_msg_dds__Header_& out, Borrowed& borrowed) {
  toWire(value.stamp, out.stamp, borrowed);
  toWire(value.frame_id, out.frame_id, borrowed);
}
template <typename T, std::size_t N, typename W>
inline void toWire(const std::array<T, N>& value, W (&out)[N], Borrowed& /*borrowed*/) {
  std::copy(value.begin(), value.end(), out);
}
inline void toWire(const Doubles& value, dds_sequence_double& out, Borrowed& /*borrowed*/) {
  out = borrow<dds_sequence_double>(value);
}
inline void toWire(const Counts& value, dds_sequence_unsigned_long_long& out,
                   Borrowed& /*borrowed*/) {
  out = borrow<dds_sequence_unsigned_long_long>(value);
}
inline void toWire(const Strings& value, dds_sequence_string& out, Borrowed& borrowed) {
  std::vector<char*>& names = borrowed.strings.emplace_back();
  for (const std::string& name : value) {
    names.push_back(const_cast<char*>(name.c_str()));
  }
  out = borrow<dds_sequence_string>(names);
}

#define COMPLY_TO_WIRE(Type, member, wire, init, doc) toWire(message.member, out.wire, borrowed);

inline void toWire(const ChunkTimingMessage& message, WireChunkTiming& out, Borrowed& borrowed) {
  COMPLY_CHUNK_TIMING_FIELDS(COMPLY_TO_WIRE)
}
inline void toWire(const ChunkTimings& value, dds_sequence_comply_msgs_msg_dds__ChunkTiming_& out,
                   Borrowed& borrowed) {
  std::vector<WireChunkTiming>& timings = borrowed.chunk_timings.emplace_back(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    toWire(value[i], timings[i], borrowed);
  }
  out = borrow<dds_sequence_comply_msgs_msg_dds__ChunkTiming_>(timings);
}

inline void toWire(const CommandOutcomeMessage& message, WireOutcome& out, Borrowed& borrowed) {
  COMPLY_COMMAND_OUTCOME_FIELDS(COMPLY_TO_WIRE)
}
inline void toWire(const Outcomes& value, dds_sequence_comply_msgs_msg_dds__CommandOutcome_& out,
                   Borrowed& borrowed) {
  std::vector<WireOutcome>& outcomes = borrowed.outcomes.emplace_back(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    toWire(value[i], outcomes[i], borrowed);
  }
  out = borrow<dds_sequence_comply_msgs_msg_dds__CommandOutcome_>(outcomes);
}

// ---- from the idlc types ----

template <typename W, typename T>
requires(std::is_arithmetic_v<T> || std::is_enum_v<T>) void fromWire(const W& in, T& value) {
  value = static_cast<T>(in);
}
inline void fromWire(const char* in, std::string& value) {
  value = text(in);
}
inline void fromWire(const builtin_interfaces_msg_dds__Time_& in, Stamp& value) {
  value = fromWireStamp(in.sec, in.nanosec);
}
inline void fromWire(const std_msgs_msg_dds__Header_& in, Header& value) {
  fromWire(in.stamp, value.stamp);
  fromWire(in.frame_id, value.frame_id);
}
template <typename W, std::size_t N, typename T>
inline void fromWire(const W (&in)[N], std::array<T, N>& value) {
  std::copy(std::begin(in), std::end(in), value.begin());
}
inline void fromWire(const dds_sequence_double& in, Doubles& value) {
  value = copyOf<double>(in);
}
inline void fromWire(const dds_sequence_unsigned_long_long& in, Counts& value) {
  value = copyOf<std::uint64_t>(in);
}
inline void fromWire(const dds_sequence_string& in, Strings& value) {
  value.clear();
  for (std::uint32_t i = 0; i < in._length; ++i) {
    value.push_back(text(in._buffer[i]));
  }
}

#define COMPLY_FROM_WIRE(Type, member, wire, init, doc) fromWire(in.wire, message.member);

inline void fromWire(const WireChunkTiming& in, ChunkTimingMessage& message) {
  COMPLY_CHUNK_TIMING_FIELDS(COMPLY_FROM_WIRE)
}
inline void fromWire(const dds_sequence_comply_msgs_msg_dds__ChunkTiming_& in,
                     ChunkTimings& value) {
  value.assign(in._length, ChunkTimingMessage{});
  for (std::uint32_t i = 0; i < in._length; ++i) {
    fromWire(in._buffer[i], value[i]);
  }
}
inline void fromWire(const WireOutcome& in, CommandOutcomeMessage& message) {
  COMPLY_COMMAND_OUTCOME_FIELDS(COMPLY_FROM_WIRE)
}
inline void fromWire(const dds_sequence_comply_msgs_msg_dds__CommandOutcome_& in, Outcomes& value) {
  value.assign(in._length, CommandOutcomeMessage{});
  for (std::uint32_t i = 0; i < in._length; ++i) {
    fromWire(in._buffer[i], value[i]);
  }
}

}  // namespace comply::transport::wire
