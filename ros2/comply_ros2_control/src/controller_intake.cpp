// What the controller takes from its topics, off the real-time thread (comply_controller.hpp):
// commands and chunks through the gate, their senders named and departed writers released,
// requests and committed requests answered, each also recorded and viewed as received.

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "comply/core/clock.hpp"
#include "comply_ros2_control/comply_controller.hpp"
#include "comply_ros2_control/message_conversion.hpp"

namespace comply_ros2_control {

template <typename Command>
template <typename Message>
void ComplyController<Command>::noteReceived(const Message& message) {
  const comply::transport::Stamp now = comply::transport::Stamp::now();
  if (recording_) {
    recording_->received(message, now);
  }
  if (view_) {
    view_->received(message, now);
  }
}

template <typename Command>
void ComplyController<Command>::onCommand(const CommandMessage& message,
                                          const rclcpp::MessageInfo& info) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;  // a configure that failed after the subscription existed
  }
  std::string malformed;
  const Command command = fromMessage(message, malformed);
  if (malformed.empty() && (recording_ || view_)) {
    noteReceived(comply::transport::CommandMessageOf<Command>{headerOf(message.header), command});
  }
  offerToGate(message.header, info, *command_writers_, malformed,
              [&](std::int64_t stamp_ns) { return wrapper_->submit(command, stamp_ns); });
}

template <typename Command>
void ComplyController<Command>::onChunk(const ChunkMessage& message,
                                        const rclcpp::MessageInfo& info) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;
  }
  std::string malformed;
  const comply::Chunk<Command> chunk = fromMessage(message, malformed);
  if (malformed.empty() && (recording_ || view_)) {
    noteReceived(comply::transport::ChunkMessageOf<Command>{headerOf(message.header), chunk});
  }
  const double now_s = comply::stampSeconds(get_node()->now().nanoseconds());
  offerToGate(message.header, info, *chunk_writers_, malformed,
              [&](std::int64_t stamp_ns) { return wrapper_->submitChunk(chunk, now_s, stamp_ns); });
}

template <typename Command>
template <typename Header, typename Submit>
void ComplyController<Command>::offerToGate(const Header& header, const rclcpp::MessageInfo& info,
                                            WriterIdentity& writers, const std::string& malformed,
                                            Submit&& submit) {
  // A sender that left releases the topics before the next one is judged.
  releaseDeparted();
  const WriterOf writer = writers.of(info.get_rmw_message_info());
  comply::pipeline::Offer offer;
  offer.stamp_ns =
      static_cast<std::int64_t>(header.stamp.sec) * 1'000'000'000 + header.stamp.nanosec;
  offer.kind = std::is_same_v<Command, comply::CartesianCommand>
                   ? comply::pipeline::CommandKind::kCartesian
                   : comply::pipeline::CommandKind::kJoint;
  offer.publisher = writer.publisher;
  offer.participant = writer.participant;
  offer.sender = writer.sender;
  offer.malformed = malformed;
  offer.now_ns = comply::monotonicNanoseconds();
  offer.clock_ns = get_node()->now().nanoseconds();  // the node's clock: ROS time, or /clock
  offer.nanosec = header.stamp.nanosec;
  const bool active = wrapper_->diagnostics().state != comply::pipeline::WrapperState::kInactive;
  const comply::pipeline::CommandReason refused = gate_->offer(offer, active, submit);
  if (refused != comply::pipeline::CommandReason::kNone) {
    RCLCPP_WARN_THROTTLE(
        get_node()->get_logger(), *get_node()->get_clock(), 1000,
        "command rejected (%s); every outcome, with its reason, is on ~/diagnostics",
        std::string(comply::pipeline::toString(refused)).c_str());
  }
  releaseIfGone(writer.publisher);
}

template <typename Command>
void ComplyController<Command>::releaseDeparted() {
  departed_.clear();
  if (command_writers_->namesSenders() && chunk_writers_->namesSenders()) {
    command_writers_->noteDepartures(departed_);
    chunk_writers_->noteDepartures(departed_);
  } else if (gate_->publisher() != 0 && command_subscription_->get_publisher_count() == 0 &&
             chunk_subscription_->get_publisher_count() == 0) {
    departed_.push_back(gate_->publisher());  // no sender named: gone when no one publishes
  }
  for (const std::uint64_t publisher : departed_) {
    releaseWriter(publisher);
  }
}

template <typename Command>
void ComplyController<Command>::releaseIfGone(std::uint64_t publisher) {
  if (command_writers_->namesSenders() && chunk_writers_->namesSenders() &&
      !command_writers_->isMatched(publisher) && !chunk_writers_->isMatched(publisher)) {
    releaseWriter(publisher);
  }
}

template <typename Command>
void ComplyController<Command>::releaseWriter(std::uint64_t publisher) {
  if (const std::uint64_t chunk = gate_->releasePublisher(publisher); chunk != 0) {
    wrapper_->dropWaitingChunk(chunk);
  }
}

template <typename Command>
void ComplyController<Command>::onResetFault(std_srvs::srv::Trigger::Response& response) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    response.success = false;
    response.message = "not configured";
    return;
  }
  const comply::pipeline::DiagnosticsSnapshot diagnostics = wrapper_->diagnostics();
  const bool in_fault = diagnostics.state == comply::pipeline::WrapperState::kFault;
  wrapper_
      ->reset();  // either way it clears the stamp floor: a stamp that ran ahead locks no one out
  response.success = in_fault || diagnostics.reflex_latched;
  response.message = in_fault ? "reset requested: the law runs again from the next cycle"
                     : diagnostics.reflex_latched
                         ? "reset requested: the contact reflex's hold ends at the measured pose"
                         : "not in FAULT: nothing to reset (stamp floor cleared)";
}

template <typename Command>
void ComplyController<Command>::onRequest(const comply_msgs::msg::Request& message,
                                          const rclcpp::MessageInfo& info) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;
  }
  releaseDeparted();
  // Every request has an outcome, as under `comply run`: its sender learns whether it was
  // carried out or why not.
  const WriterOf writer = request_writers_->of(info.get_rmw_message_info());
  if (recording_ || view_) {
    comply::transport::RequestMessage received;
    received.header = headerOf(message.header);
    received.request = static_cast<comply::transport::RequestType>(message.request);
    noteReceived(received);
  }
  const std::uint32_t nanosec = message.header.stamp.nanosec;
  const std::int64_t stamp_ns =
      static_cast<std::int64_t>(message.header.stamp.sec) * 1'000'000'000 + nanosec;
  const auto settle = [&](comply::pipeline::CommandReason reason, std::string refusal) {
    gate_->settleRequest(stamp_ns, writer.sender, reason, std::move(refusal), nanosec);
  };
  if (nanosec >= 1'000'000'000U) {
    const std::string why = "invalid_stamp: header.stamp.nanosec " + std::to_string(nanosec) +
                            " is out of range (0 to 999999999)";
    gate_->noteRefusal("request refused: " + why);
    settle(comply::pipeline::CommandReason::kInvalidStamp, why);
    return;
  }
  if (message.request == comply_msgs::msg::Request::REQUEST_PROBE) {
    settle(comply::pipeline::CommandReason::kNone, "");  // nothing to do, nothing to refuse
    return;
  }
  // While one process commands the arm, another cannot reset it or tare its sensor.
  std::string why;
  if (!gate_->admitRequest(writer.participant, comply::monotonicNanoseconds(), why)) {
    settle(comply::pipeline::CommandReason::kOtherPublisher, why);
    return;
  }
  const std::string refused = carryOut(message.request);
  if (!refused.empty()) {
    gate_->noteRefusal(refused);
  }
  settle(comply::pipeline::CommandReason::kNone, refused);
}

template <typename Command>
void ComplyController<Command>::onCommittedRequest(
    const comply_msgs::msg::CommittedRequest& message, const rclcpp::MessageInfo& info) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;
  }
  comply::transport::Sample<comply::transport::CommittedRequestMessage> sample;
  sample.message = fromMessage(message);
  const WriterOf writer = committed_writers_->of(info.get_rmw_message_info());
  sample.publisher = writer.publisher;
  sample.participant = writer.participant;
  sample.sender = writer.sender;
  // The node's clock: a chunk's times are on it (onChunk), and so are the times asked for.
  toMessage(committed_->answer(sample, get_node()->now().nanoseconds()), committed_message_);
  committed_publisher_->publish(committed_message_);
}

template <typename Command>
std::string ComplyController<Command>::carryOut(std::uint8_t request) {
  using comply_msgs::msg::Request;
  const std::string name = get_node()->get_name();
  switch (request) {
    case Request::REQUEST_ACTIVATE:
    case Request::REQUEST_DEACTIVATE:
      return std::string(request == Request::REQUEST_ACTIVATE ? "activate" : "deactivate") +
             ": the controller manager activates and deactivates a ros2_control controller (ros2 "
             "control switch_controllers --" +
             (request == Request::REQUEST_ACTIVATE ? "activate " : "deactivate ") + name + ")";
    case Request::REQUEST_RESET:
      // Either way it clears the stamp floor; the cycle decides whether FAULT is left.
      return wrapper_->reset() != 0 ? "" : "reset: the intake queue is full, send it again";
    case Request::REQUEST_TARE: {
      const std::string why_not = wrapper_->tare();
      return why_not.empty() ? "" : "tare: " + why_not;
    }
    default:
      return "request " + std::to_string(request) + " is not one this host knows";
  }
}

// The members defined here, for both kinds (the class itself is instantiated in
// comply_controller.cpp, with the members defined there).
#define COMPLY_INTAKE_MEMBERS(Command)                                                             \
  template void ComplyController<Command>::onCommand(                                              \
      const ComplyController<Command>::CommandMessage&, const rclcpp::MessageInfo&);               \
  template void ComplyController<Command>::onChunk(const ComplyController<Command>::ChunkMessage&, \
                                                   const rclcpp::MessageInfo&);                    \
  template void ComplyController<Command>::releaseDeparted();                                      \
  template void ComplyController<Command>::releaseIfGone(std::uint64_t);                           \
  template void ComplyController<Command>::releaseWriter(std::uint64_t);                           \
  template void ComplyController<Command>::onResetFault(std_srvs::srv::Trigger::Response&);        \
  template void ComplyController<Command>::onRequest(const comply_msgs::msg::Request&,             \
                                                     const rclcpp::MessageInfo&);                  \
  template void ComplyController<Command>::onCommittedRequest(                                     \
      const comply_msgs::msg::CommittedRequest&, const rclcpp::MessageInfo&);                      \
  template std::string ComplyController<Command>::carryOut(std::uint8_t);
COMPLY_INTAKE_MEMBERS(comply::JointCommand)
COMPLY_INTAKE_MEMBERS(comply::CartesianCommand)
#undef COMPLY_INTAKE_MEMBERS

}  // namespace comply_ros2_control
