#pragma once
// comply_msgs commands and chunks as comply's values, and back. They go field by field through
// comply's schema table (the .msg files are generated from it), so a field added to the table
// needs no code here. The state and diagnostics the controllers publish go through the message
// tables (comply/transport/message_copy.hpp); the committed request and its answer through both.

#include <string>

#include "comply/core/chunk.hpp"
#include "comply/core/commands.hpp"
#include "comply/transport/messages.hpp"
#include "comply_msgs/msg/cartesian_chunk.hpp"
#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/committed.hpp"
#include "comply_msgs/msg/committed_request.hpp"
#include "comply_msgs/msg/joint_chunk.hpp"
#include "comply_msgs/msg/joint_command.hpp"

namespace comply_ros2_control {

/// The command a message carries; its stamp is header.stamp. `malformed` names a joint vector
/// longer than any controller's (the command is then refused before it reaches the wrapper).
comply::CartesianCommand fromMessage(const comply_msgs::msg::CartesianCommand& message,
                                     std::string& malformed);
comply::JointCommand fromMessage(const comply_msgs::msg::JointCommand& message,
                                 std::string& malformed);

/// The chunk a message carries: its stamp is header.stamp, each waypoint's time its
/// header.stamp; `malformed` as for commands, naming the waypoint.
comply::CartesianChunk fromMessage(const comply_msgs::msg::CartesianChunk& message,
                                   std::string& malformed);
comply::JointChunk fromMessage(const comply_msgs::msg::JointChunk& message, std::string& malformed);

/// A command as its message, every field through its kind's table (header untouched).
void toMessage(const comply::CartesianCommand& command,
               comply_msgs::msg::CartesianCommand& message);
void toMessage(const comply::JointCommand& command, comply_msgs::msg::JointCommand& message);

/// A message header as comply's transport holds it.
comply::transport::Header headerOf(const std_msgs::msg::Header& header);

/// A committed request as every host takes it (comply::host::CommittedAnswers).
comply::transport::CommittedRequestMessage fromMessage(
    const comply_msgs::msg::CommittedRequest& message);
/// The answer to a committed request as its message; `message`'s lists are reused.
void toMessage(const comply::transport::CommittedMessage& answer,
               comply_msgs::msg::Committed& message);

}  // namespace comply_ros2_control
