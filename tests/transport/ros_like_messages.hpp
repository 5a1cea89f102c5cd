#pragma once
// Structs shaped as rosidl generates ROS 2's comply_msgs from msg/*.msg: a member per field named
// by its wire name, uint8 for the enumerations, builtin_interfaces/Time and std_msgs/Header as
// their own structs. copyMessage() (message_copy.hpp) is tested on them without a ROS 2 install;
// the ROS 2 controllers use it on the real ones.

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport::ros_like {

struct Time {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

struct Header {
  Time stamp;
  std::string frame_id;
};

struct CommandOutcome;
struct ChunkTiming;

/// The rosidl type of a table row's C++ type.
template <typename T, typename = void>
struct Of {
  using type = T;
};
template <typename T>
struct Of<T, std::enable_if_t<std::is_enum_v<T>>> {
  using type = std::uint8_t;
};
template <>
struct Of<Stamp> {
  using type = Time;
};
template <>
struct Of<transport::Header> {
  using type = Header;
};
template <>
struct Of<ChunkTimings> {
  using type = std::vector<ChunkTiming>;
};
template <>
struct Of<Outcomes> {
  using type = std::vector<CommandOutcome>;
};

#define COMPLY_ROS_LIKE_MEMBER(Type, member, wire, init, doc) \
  typename ::comply::transport::ros_like::Of<Type>::type wire{};

struct ChunkTiming {
  COMPLY_CHUNK_TIMING_FIELDS(COMPLY_ROS_LIKE_MEMBER)
};
struct CommandOutcome {
  COMPLY_COMMAND_OUTCOME_FIELDS(COMPLY_ROS_LIKE_MEMBER)
};
struct ControllerState {
  COMPLY_CONTROLLER_STATE_FIELDS(COMPLY_ROS_LIKE_MEMBER)
};
struct Diagnostics {
  COMPLY_DIAGNOSTICS_FIELDS(COMPLY_ROS_LIKE_MEMBER)
};

}  // namespace comply::transport::ros_like
