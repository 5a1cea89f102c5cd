#include "comply_ros2_control/message_conversion.hpp"

#include <algorithm>
#include <sstream>
#include <type_traits>
#include <variant>

#include "comply/schema/schema.hpp"
#include "comply/schema/table.hpp"

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

double seconds(const builtin_interfaces::msg::Time& stamp) {
  return comply::stampSeconds(static_cast<std::int64_t>(stamp.sec) * 1'000'000'000 + stamp.nanosec);
}

builtin_interfaces::msg::Time stampOf(double seconds_since_epoch) {
  builtin_interfaces::msg::Time stamp;
  const auto nanoseconds = static_cast<std::int64_t>(seconds_since_epoch * 1e9);
  stamp.sec = static_cast<std::int32_t>(nanoseconds / 1'000'000'000);
  stamp.nanosec = static_cast<std::uint32_t>(nanoseconds % 1'000'000'000);
  return stamp;
}

#define COMPLY_ROS_FROM(name, group, kind, type, unit, constraint, role, init, doc) \
  fromField<FieldKind::kind>(message.name, command.name, #name, malformed);

void setPassivity(const comply::pipeline::PassivitySnapshot& passivity,
                  comply_msgs::msg::ControllerState& message) noexcept {
  message.passivity = passivity.enabled;
  message.tank_energy = passivity.tank_energy_j;
  message.nullspace_tank_energy = passivity.nullspace_tank_energy_j;
  message.energy_injected = passivity.injected_j;
  message.energy_dissipated = passivity.dissipated_j;
  message.energy_refused = passivity.refused_j;
  message.gain_fraction = passivity.gain_fraction;
}

template <typename Values>
void copyInto(const Values& values, std::vector<double>& out) noexcept {
  for (std::size_t i = 0; i < out.size() && i < static_cast<std::size_t>(values.size()); ++i) {
    out[i] = values[static_cast<Eigen::Index>(i)];
  }
}

}  // namespace

comply::CartesianCommand fromMessage(const comply_msgs::msg::CartesianCommand& message,
                                     std::string& malformed) {
  comply::CartesianCommand command;
  command.stamp_s = seconds(message.header.stamp);
  command.fields = static_cast<comply::CommandField>(message.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_ROS_FROM)
  return command;
}

comply::JointCommand fromMessage(const comply_msgs::msg::JointCommand& message,
                                 std::string& malformed) {
  comply::JointCommand command;
  command.stamp_s = seconds(message.header.stamp);
  command.fields = static_cast<comply::CommandField>(message.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_ROS_FROM)
  return command;
}

namespace {

/// A chunk's waypoints are commands whose header.stamp is their time. The wire bounds them at
/// comply::kMaxChunkWaypoints; validation checks the count again.
template <typename Command, typename Message>
comply::Chunk<Command> chunkFromMessage(const Message& message, std::string& malformed) {
  comply::Chunk<Command> chunk;
  chunk.stamp_s = seconds(message.header.stamp);
  chunk.fields = static_cast<comply::CommandField>(message.fields);
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

void prepareState(const comply::pipeline::Controller& controller,
                  comply_msgs::msg::ControllerState& message) {
  const auto& config = controller.resolved().config;
  const auto dof = static_cast<std::size_t>(controller.dof());
  message.header.frame_id = config.base_frame;
  message.joint_names = config.joints;
  message.command_kind = controller.resolved().cartesian()
                             ? comply_msgs::msg::ControllerState::COMMAND_KIND_CARTESIAN
                             : comply_msgs::msg::ControllerState::COMMAND_KIND_JOINT;
  message.position.assign(dof, 0.0);
  message.velocity.assign(dof, 0.0);
  message.effort.assign(dof, 0.0);
  message.torque_command.assign(dof, 0.0);
  message.reference_joint_position.assign(controller.resolved().cartesian() ? 0 : dof, 0.0);
}

void fillState(const comply::pipeline::Controller& controller, const comply::JointState& state,
               std::span<const double> torque, std::uint64_t cycle,
               const builtin_interfaces::msg::Time& stamp,
               comply_msgs::msg::ControllerState& message) noexcept {
  message.header.stamp = stamp;
  const comply::pipeline::Diagnostics& diagnostics = controller.diagnostics();
  message.state = static_cast<std::uint8_t>(diagnostics.state.load(std::memory_order_relaxed));
  message.cycle = cycle;
  copyInto(state.position, message.position);
  copyInto(state.velocity, message.velocity);
  copyInto(state.effort, message.effort);
  for (std::size_t i = 0; i < message.torque_command.size() && i < torque.size(); ++i) {
    message.torque_command[i] = torque[i];
  }
  const comply::model::Data& data = controller.modelData();
  for (int i = 0; i < 3; ++i) {
    message.tcp_position[static_cast<std::size_t>(i)] = data.tip_position[i];
  }
  comply::schema::toXyzw(data.tip_orientation, message.tcp_orientation.data());
  if (data.jacobian.cols() == controller.dof()) {
    const comply::Vector6d twist = data.jacobian * state.velocity;
    for (int i = 0; i < 6; ++i) {
      message.tcp_twist[static_cast<std::size_t>(i)] = twist[i];
    }
  }
  std::visit(
      [&message](const auto& bus) {
        message.reference_stamp = stampOf(bus.stamp_s);
        message.reference_fields = bus.fields;
        if constexpr (std::is_same_v<std::decay_t<decltype(bus)>, comply_cartesian_command>) {
          for (std::size_t i = 0; i < 3; ++i) {
            message.reference_position[i] = bus.position[i];
          }
          for (std::size_t i = 0; i < 4; ++i) {
            message.reference_orientation[i] = bus.orientation[i];
          }
        } else {
          for (std::size_t i = 0; i < message.reference_joint_position.size(); ++i) {
            message.reference_joint_position[i] = bus.position[i];
          }
        }
      },
      controller.activeCommand());
  setPassivity(diagnostics.passivity(), message);  // atomics only: no allocation
}

void fillDiagnostics(const comply::pipeline::DiagnosticsSnapshot& snapshot, double period_s,
                     const comply::pipeline::GateCounts& counts, std::uint64_t publisher,
                     comply_msgs::msg::Diagnostics& message) {
  message.state = static_cast<std::uint8_t>(snapshot.state);
  message.cycles = snapshot.cycles;
  message.period = period_s;
  message.commands_received = counts.received;
  message.commands_applied = counts.applied;
  message.commands_rejected = counts.rejected;
  message.rejections.assign(counts.per_reason.begin(), counts.per_reason.end());
  message.watchdog_timeouts = snapshot.watchdog_timeouts;
  message.faults = snapshot.faults;
  message.rate_limit_hits = snapshot.rate_limit_hits;
  message.effort_limit_hits = snapshot.effort_limit_hits;
  message.last_fault = snapshot.last_fault;
  message.last_rejection = snapshot.last_rejection;
  std::ostringstream holder;
  if (publisher != 0) {
    holder << std::hex << publisher;
  }
  message.publisher = holder.str();
}

namespace {
builtin_interfaces::msg::Time timeOf(std::int64_t nanoseconds) {
  builtin_interfaces::msg::Time time;
  time.sec = static_cast<std::int32_t>(nanoseconds / 1'000'000'000);
  time.nanosec = static_cast<std::uint32_t>(nanoseconds % 1'000'000'000);
  return time;
}
}  // namespace

comply_msgs::msg::CommandOutcome toMessage(const comply::pipeline::CommandOutcome& outcome) {
  comply_msgs::msg::CommandOutcome message;
  message.stamp = timeOf(outcome.stamp_ns);
  message.command_kind = static_cast<std::uint8_t>(outcome.kind);
  message.outcome = outcome.applied ? message.OUTCOME_APPLIED : message.OUTCOME_REJECTED;
  message.reason = static_cast<std::uint8_t>(outcome.reason);
  message.cycle = outcome.cycle;
  message.received = timeOf(outcome.received_ns);
  message.applied = timeOf(outcome.applied_ns);
  message.message = outcome.message;
  std::copy(outcome.sender.begin(), outcome.sender.end(), message.sender.begin());
  return message;
}

}  // namespace comply_ros2_control
