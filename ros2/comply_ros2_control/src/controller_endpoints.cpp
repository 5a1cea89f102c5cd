// The controller's endpoints, made at configure (comply_controller.hpp): its topics, services and
// timers, the recording and the live view; and what its timers publish, built off the real-time
// thread from the cycle's state sample and the gate's outcomes.

#include <chrono>
#include <stdexcept>
#include <string>

#include "comply/transport/message_copy.hpp"
#include "comply_ros2_control/comply_controller.hpp"
#include "controller_parameter_names.hpp"

namespace comply_ros2_control {

using namespace parameter_names;  // NOLINT(google-build-using-namespace): the package's own names

template <typename Command>
void ComplyController<Command>::createEndpoints() {
  const auto node = get_node();
  const double state_rate_hz = node->get_parameter(kStateRate).as_double();
  const double diagnostics_rate_hz = node->get_parameter(kDiagnosticsRate).as_double();
  if (!(state_rate_hz > 0.0) || !(diagnostics_rate_hz > 0.0)) {
    throw std::invalid_argument(std::string(kStateRate) + " and " + kDiagnosticsRate +
                                " must be positive");
  }
  const unsigned update_rate_hz = get_update_rate() > 0 ? get_update_rate() : 1000;
  nominal_period_s_ = 1.0 / update_rate_hz;
  loop_ = std::make_unique<comply::host::LoopCounters>();
  sampler_ = std::make_unique<comply::host::StateSampler<Command>>(*wrapper_);
  sample_ = {};
  samples_ = std::make_unique<comply::TripleBuffer<comply::host::StateSample>>();
  // The QoS of `comply run`'s topics: state as sensor data, diagnostics reliable and deep.
  state_publisher_ =
      node->create_publisher<comply_msgs::msg::ControllerState>("~/state", rclcpp::SensorDataQoS());
  diagnostics_publisher_ = node->create_publisher<comply_msgs::msg::Diagnostics>(
      "~/diagnostics", rclcpp::QoS(100).reliable());
  command_subscription_ = node->create_subscription<CommandMessage>(
      // Deeper than ROS's 10: a burst that arrives while the executor is busy waits here instead
      // of being dropped unaccounted (comply run keeps all; rclcpp cannot bound a keep-all).
      CommandTopic<Command>::kName, rclcpp::QoS(kCommandDepth).reliable(),
      [this](const std::shared_ptr<const CommandMessage> message, const rclcpp::MessageInfo& info) {
        onCommand(*message, info);
      });
  chunk_subscription_ = node->create_subscription<ChunkMessage>(
      CommandTopic<Command>::kChunkName, rclcpp::QoS(kCommandDepth).reliable(),
      [this](const std::shared_ptr<const ChunkMessage> message, const rclcpp::MessageInfo& info) {
        onChunk(*message, info);
      });
  request_subscription_ = node->create_subscription<comply_msgs::msg::Request>(
      "~/request", rclcpp::QoS(100).reliable(),
      [this](const std::shared_ptr<const comply_msgs::msg::Request> message,
             const rclcpp::MessageInfo& info) { onRequest(*message, info); });
  // comply run's QoS for both (ROS 2's default: reliable, keep last 10).
  committed_publisher_ = node->create_publisher<comply_msgs::msg::Committed>(
      "~/committed", rclcpp::QoS(10).reliable());
  committed_subscription_ = node->create_subscription<comply_msgs::msg::CommittedRequest>(
      "~/committed_request", rclcpp::QoS(10).reliable(),
      [this](const std::shared_ptr<const comply_msgs::msg::CommittedRequest> message,
             const rclcpp::MessageInfo& info) { onCommittedRequest(*message, info); });
  committed_ = std::make_unique<comply::host::CommittedAnswers<Command>>(
      *wrapper_, resolved_->robot.base_frame);
  command_writers_.emplace(*command_subscription_);
  chunk_writers_.emplace(*chunk_subscription_);
  request_writers_.emplace(*request_subscription_);
  committed_writers_.emplace(*committed_subscription_);
  departed_.reserve(64);
  reset_service_ = node->create_service<std_srvs::srv::Trigger>(
      "~/reset_fault", [this](const std::shared_ptr<std_srvs::srv::Trigger::Request>,
                              std::shared_ptr<std_srvs::srv::Trigger::Response> response) {
        onResetFault(*response);
      });
  tare_service_ = node->create_service<std_srvs::srv::Trigger>(
      "~/tare", [this](const std::shared_ptr<std_srvs::srv::Trigger::Request>,
                       std::shared_ptr<std_srvs::srv::Trigger::Response> response) {
        const std::lock_guard<std::mutex> lock(endpoints_mutex_);
        if (!wrapper_) {
          response->success = false;
          response->message = "not configured";
          return;
        }
        const std::string why = wrapper_->tare();
        response->success = why.empty();
        response->message =
            why.empty() ? "tare requested: the next cycle's reading is the zero" : why;
      });
  openRecording();
  openView();
  state_timer_ = node->create_wall_timer(std::chrono::duration<double>(1.0 / state_rate_hz),
                                         [this] { publishState(); });
  diagnostics_timer_ = node->create_wall_timer(
      std::chrono::duration<double>(1.0 / diagnostics_rate_hz), [this] { publishDiagnostics(); });
}

template <typename Command>
void ComplyController<Command>::openRecording() {
  const std::string path = get_node()->get_parameter(kRecord).as_string();
  if (path.empty()) {
    return;
  }
  try {
    recording_ = std::make_unique<comply::host::HostRecording>(
        path, resolved_, get_node()->get_name(),
        comply::record::StringMap{{"host", "ros2_control"},
                                  {"rate_hz", std::to_string(1.0 / nominal_period_s_)}},
        // update() never waits for the disk: a full lane drops, and counts.
        comply::host::HostRecordingOptions{.when_full = comply::record::WhenFull::kDrop});
  } catch (const std::exception& error) {
    throw std::runtime_error(std::string("parameter ") + kRecord + ": " + error.what());
  }
  RCLCPP_INFO(get_node()->get_logger(), "recording every cycle to %s", path.c_str());
}

template <typename Command>
void ComplyController<Command>::openView() {
  const std::string address = get_node()->get_parameter(kFoxglove).as_string();
  if (address.empty()) {
    return;
  }
  try {
    view_ = std::make_unique<comply::host::LiveView>(comply::host::parseViewAddress(address),
                                                     resolved_, get_node()->get_name());
  } catch (const std::exception& error) {
    throw std::runtime_error(std::string("parameter ") + kFoxglove + ": " + error.what());
  }
  RCLCPP_INFO(get_node()->get_logger(), "live view: open %s in Foxglove", view_->url().c_str());
}

template <typename Command>
void ComplyController<Command>::publishState() {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_ || !samples_->update()) {
    return;  // no cycle since the last message (inactive)
  }
  comply_msgs::msg::ControllerState message;
  comply::transport::copyMessage(
      comply::host::stateMessage(samples_->read(), wrapper_->controller().resolved()), message);
  state_publisher_->publish(message);
}

template <typename Command>
void ComplyController<Command>::publishDiagnostics() {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;
  }
  releaseDeparted();
  gate_->settle();
  comply::transport::DiagnosticsMessage diagnostics = comply::host::diagnosticsMessage(
      wrapper_->diagnostics(), *loop_, nominal_period_s_, gate_->counts(), gate_->publisher(),
      get_node()->get_name(), comply::host::outcomeMessages(gate_->takeOutcomes()));
  diagnostics.header.stamp =
      comply::transport::Stamp::fromNanoseconds(get_node()->now().nanoseconds());
  if (recording_) {
    const comply::record::RecorderStats stats = recording_->stats();
    diagnostics.records_dropped = stats.dropped;
    diagnostics.recording =
        stats.error.empty() ? recording_->path() : "stopped early: " + stats.error;
    for (const comply::transport::CommandOutcomeMessage& outcome : diagnostics.outcomes) {
      recording_->outcome(outcome);
    }
    recording_->diagnostics(diagnostics);
  }
  if (view_) {
    for (const comply::transport::CommandOutcomeMessage& outcome : diagnostics.outcomes) {
      view_->outcome(outcome);
    }
    view_->diagnostics(diagnostics);
  }
  comply_msgs::msg::Diagnostics message;
  comply::transport::copyMessage(diagnostics, message);
  diagnostics_publisher_->publish(message);
}

// The members defined here, for both kinds (the class itself is instantiated in
// comply_controller.cpp, with the members defined there).
#define COMPLY_ENDPOINT_MEMBERS(Command)                      \
  template void ComplyController<Command>::createEndpoints(); \
  template void ComplyController<Command>::openRecording();   \
  template void ComplyController<Command>::openView();        \
  template void ComplyController<Command>::publishState();    \
  template void ComplyController<Command>::publishDiagnostics();
COMPLY_ENDPOINT_MEMBERS(comply::JointCommand)
COMPLY_ENDPOINT_MEMBERS(comply::CartesianCommand)
#undef COMPLY_ENDPOINT_MEMBERS

}  // namespace comply_ros2_control
