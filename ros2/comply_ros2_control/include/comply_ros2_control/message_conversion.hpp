#pragma once
// comply_msgs as comply's values and back. The commands go field by field through comply's schema
// table (the .msg files are generated from it), so a field added to the table needs no code here.

#include <span>
#include <string>

#include "comply/core/chunk.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply_msgs/msg/cartesian_chunk.hpp"
#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/command_outcome.hpp"
#include "comply_msgs/msg/controller_state.hpp"
#include "comply_msgs/msg/diagnostics.hpp"
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

/// Sizes the per-joint members of `message` and sets what never changes (joint names, frame).
void prepareState(const comply::pipeline::Controller& controller,
                  comply_msgs::msg::ControllerState& message);
/// Fills a message prepared by prepareState() from the cycle that just ran. Real-time: copies into
/// the members as sized, allocates nothing.
void fillState(const comply::pipeline::Controller& controller, const comply::JointState& state,
               std::span<const double> torque, std::uint64_t cycle,
               const builtin_interfaces::msg::Time& stamp,
               comply_msgs::msg::ControllerState& message) noexcept;

/// The wrapper's counters and texts and the command gate's accounting as a Diagnostics message
/// (not real-time: copies strings); the caller sets the header, the timing and the outcomes.
void fillDiagnostics(const comply::pipeline::DiagnosticsSnapshot& snapshot, double period_s,
                     const comply::pipeline::GateCounts& counts, std::uint64_t publisher,
                     comply_msgs::msg::Diagnostics& message);

/// A command gate's outcome as the wire's CommandOutcome (the numbers are the same).
comply_msgs::msg::CommandOutcome toMessage(const comply::pipeline::CommandOutcome& outcome);

}  // namespace comply_ros2_control
