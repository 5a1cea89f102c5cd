#include "comply_ros2_control/message_conversion.hpp"

#include <algorithm>
#include <string>
#include <type_traits>

#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"
#include "comply/transport/messages.hpp"

namespace comply_ros2_control {
namespace {

using comply::schema::FieldKind;

template <FieldKind K, typename MessageValue, typename Value>
void fromField(const MessageValue& in, Value& value, const char* name, std::string& malformed) {
  if constexpr (K == FieldKind::kQuaternion) {
    value = comply::schema::fromXyzw(in.data());
  } else if constexpr (K == FieldKind::kBlock3) {
    value = comply::schema::fromRowMajor(in.data());
  } else if constexpr (K == FieldKind::kEnum) {
    value = static_cast<Value>(in);
  } else if constexpr (K == FieldKind::kJointVector) {
    if (in.size() > static_cast<std::size_t>(comply::kMaxDof)) {
      malformed = std::string(name) + " has " + std::to_string(in.size()) +
                  " entries, more than any controller's joints (" +
                  std::to_string(comply::kMaxDof) + ")";
      value.resize(0);
      return;
    }
    value = Eigen::Map<const Eigen::VectorXd>(in.data(), static_cast<Eigen::Index>(in.size()));
  } else {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      value[i] = in[static_cast<std::size_t>(i)];
    }
  }
}

template <FieldKind K, typename Value, typename MessageValue>
void toField(const Value& value, MessageValue& out) {
  if constexpr (K == FieldKind::kQuaternion) {
    comply::schema::toXyzw(value, out.data());
  } else if constexpr (K == FieldKind::kBlock3) {
    comply::schema::toRowMajor(value, out.data());
  } else if constexpr (K == FieldKind::kEnum) {
    out = static_cast<MessageValue>(value);
  } else if constexpr (K == FieldKind::kJointVector) {
    out.assign(value.data(), value.data() + value.size());
  } else {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      out[static_cast<std::size_t>(i)] = value[i];
    }
  }
}

builtin_interfaces::msg::Time rosTime(const comply::transport::Stamp& stamp) {
  builtin_interfaces::msg::Time time;
  time.sec = stamp.sec;
  time.nanosec = stamp.nanosec;
  return time;
}

comply::transport::Stamp stampOf(const builtin_interfaces::msg::Time& time) {
  return {time.sec, time.nanosec};
}

double seconds(const builtin_interfaces::msg::Time& stamp) {
  return comply::stampSeconds(static_cast<std::int64_t>(stamp.sec) * 1'000'000'000 + stamp.nanosec);
}

#define COMPLY_ROS_FROM(name, group, kind, type, unit, constraint, role, init, doc) \
  fromField<FieldKind::kind>(message.name, command.name, #name, malformed);
#define COMPLY_ROS_TO(name, group, kind, type, unit, constraint, role, init, doc) \
  toField<FieldKind::kind>(command.name, message.name);

}  // namespace

namespace {

/// A command message's command, field by field through its kind's table.
template <typename Command, typename Message>
Command commandFromMessage(const Message& message, std::string& malformed) {
  Command command;
  command.stamp_s = seconds(message.header.stamp);
  command.fields = static_cast<comply::CommandField>(message.fields);
  if constexpr (std::is_same_v<Command, comply::CartesianCommand>) {
    COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_ROS_FROM)
  } else {
    COMPLY_JOINT_COMMAND_FIELDS(COMPLY_ROS_FROM)
  }
  return command;
}

}  // namespace

void toMessage(const comply::CartesianCommand& command,
               comply_msgs::msg::CartesianCommand& message) {
  message.fields = static_cast<std::uint32_t>(command.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_ROS_TO)
}

void toMessage(const comply::JointCommand& command, comply_msgs::msg::JointCommand& message) {
  message.fields = static_cast<std::uint32_t>(command.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_ROS_TO)
}

comply::transport::Header headerOf(const std_msgs::msg::Header& header) {
  return {stampOf(header.stamp), header.frame_id};
}

comply::transport::CommittedRequestMessage fromMessage(
    const comply_msgs::msg::CommittedRequest& message) {
  comply::transport::CommittedRequestMessage request;
  request.header.stamp = stampOf(message.header.stamp);
  request.header.frame_id = message.header.frame_id;
  request.observation = stampOf(message.observation);
  request.dt_s = message.dt;
  request.count = message.count;
  return request;
}

void toMessage(const comply::transport::CommittedMessage& answer,
               comply_msgs::msg::Committed& message) {
  message.header.stamp = rosTime(answer.header.stamp);
  message.header.frame_id = answer.header.frame_id;
  message.request_stamp = rosTime(answer.request_stamp);
  std::copy(answer.sender.begin(), answer.sender.end(), message.sender.begin());
  message.command_kind = static_cast<std::uint8_t>(answer.command_kind);
  message.answered = answer.answered;
  message.known = answer.known;
  message.message = answer.message;
  const auto copyList = [](const auto& from, auto& to) {
    to.resize(from.size());
    for (std::size_t k = 0; k < from.size(); ++k) {
      to[k].header.stamp = rosTime(from[k].header.stamp);
      to[k].header.frame_id = from[k].header.frame_id;
      toMessage(from[k].command, to[k]);
    }
  };
  copyList(answer.cartesian, message.cartesian);
  copyList(answer.joint, message.joint);
}

comply::CartesianCommand fromMessage(const comply_msgs::msg::CartesianCommand& message,
                                     std::string& malformed) {
  return commandFromMessage<comply::CartesianCommand>(message, malformed);
}

comply::JointCommand fromMessage(const comply_msgs::msg::JointCommand& message,
                                 std::string& malformed) {
  return commandFromMessage<comply::JointCommand>(message, malformed);
}

namespace {

/// A chunk's waypoints are commands whose header.stamp is their time. The wire does not bound
/// them (a bound there drops a longer chunk unanswered): validation refuses more than
/// comply::kMaxChunkWaypoints as invalid_chunk.
template <typename Command, typename Message>
comply::Chunk<Command> chunkFromMessage(const Message& message, std::string& malformed) {
  comply::Chunk<Command> chunk;
  chunk.stamp_s = seconds(message.header.stamp);
  chunk.fields = static_cast<comply::CommandField>(message.fields);
  // All zero: not given (NaN), as the host's own transport reads them.
  chunk.observation_s =
      comply::transport::secondsOrNaN({message.observation.sec, message.observation.nanosec});
  chunk.takeover_s =
      comply::transport::secondsOrNaN({message.takeover.sec, message.takeover.nanosec});
  for (std::size_t k = 0; k < message.waypoints.size() && malformed.empty(); ++k) {
    const auto& waypoint = message.waypoints[k];
    chunk.waypoints.push_back({seconds(waypoint.header.stamp), fromMessage(waypoint, malformed)});
    if (!malformed.empty()) {
      malformed = "waypoint " + std::to_string(k) + ": " + malformed;
    }
  }
  return chunk;
}

}  // namespace

comply::CartesianChunk fromMessage(const comply_msgs::msg::CartesianChunk& message,
                                   std::string& malformed) {
  return chunkFromMessage<comply::CartesianCommand>(message, malformed);
}

comply::JointChunk fromMessage(const comply_msgs::msg::JointChunk& message,
                               std::string& malformed) {
  return chunkFromMessage<comply::JointCommand>(message, malformed);
}

}  // namespace comply_ros2_control
