// The live view's channels and thread (see live_view.hpp).

#include "comply/host/live_view.hpp"

#include <charconv>
#include <stdexcept>

#include "comply/host/host_recording.hpp"
#include "comply/transport/cdr.hpp"
#include "live_view_scene.hpp"

namespace comply::host {
namespace {

std::uint16_t parsePort(std::string_view text, std::string_view whole) {
  unsigned port = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), port);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || port > 65535) {
    throw std::invalid_argument("--foxglove \"" + std::string(whole) +
                                "\": the port must be a number from 0 to 65535 ([ADDRESS:]PORT)");
  }
  return static_cast<std::uint16_t>(port);
}

/// A ROS 2 message's channel, its schema the message's definition as a recording stores it.
template <typename Message>
viewer::ChannelSpec rosChannel(const std::string& topic, double max_rate_hz = 0.0) {
  const std::string_view type = transport::rosTypeName<Message>();
  return {.topic = topic,
          .encoding = "cdr",
          .schema_name = std::string(type),
          .schema_encoding = "ros2msg",
          .schema = transport::ros2MessageDefinition(type),
          .max_rate_hz = max_rate_hz};
}

viewer::ServerOptions serverOptions(const LiveViewOptions& options, const std::string& name) {
  return {.address = options.address,
          .port = options.port,
          .name = name,
          .channel_queue_bytes = options.channel_queue_bytes};
}

}  // namespace

LiveViewOptions parseViewAddress(std::string_view text) {
  LiveViewOptions options;
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) {
    options.port = parsePort(text, text);
    return options;
  }
  std::string_view address = text.substr(0, colon);
  if (address.size() >= 2 && address.front() == '[' && address.back() == ']') {
    address = address.substr(1, address.size() - 2);
  }
  if (address.empty()) {
    throw std::invalid_argument("--foxglove \"" + std::string(text) +
                                "\": an address before the ':' ([ADDRESS:]PORT)");
  }
  options.address = std::string(address);
  options.port = parsePort(text.substr(colon + 1), text);
  return options;
}

std::string describeViewStats(const std::vector<viewer::ChannelStats>& stats) {
  std::uint64_t sent = 0;
  std::uint64_t dropped = 0;
  std::string per_channel;
  for (const viewer::ChannelStats& channel : stats) {
    sent += channel.sent;
    dropped += channel.dropped;
    if (channel.dropped > 0) {
      per_channel +=
          (per_channel.empty() ? "" : ", ") + channel.topic + " " + std::to_string(channel.dropped);
    }
  }
  return "live view: " + std::to_string(sent) + " messages sent to viewers, " +
         std::to_string(dropped) + " dropped for slow viewers" +
         (per_channel.empty() ? "" : " (" + per_channel + ")");
}

LiveView::LiveView(const LiveViewOptions& options,
                   std::shared_ptr<const pipeline::ResolvedController> resolved,
                   const std::string& name)
    : resolved_(std::move(resolved)), server_(serverOptions(options, name)) {
  const std::string prefix = "/" + name + "/";
  state_channel_ = server_.addChannel(
      rosChannel<transport::ControllerStateMessage>(prefix + "state", options.state_rate_hz));
  cycle_channel_ = server_.addChannel(
      rosChannel<transport::CycleRecordMessage>(prefix + "cycle", options.state_rate_hz));
  diagnostics_channel_ =
      server_.addChannel(rosChannel<transport::DiagnosticsMessage>(prefix + "diagnostics"));
  outcome_channel_ =
      server_.addChannel(rosChannel<transport::CommandOutcomeMessage>(prefix + "outcome"));
  senders_ =
      SenderChannelIds<viewer::ChannelId>(prefix, [this](const std::string& topic, auto message) {
        return server_.addChannel(rosChannel<typename decltype(message)::type>(topic));
      });
  scene_ = std::make_unique<Scene>(server_, *resolved_, name, options.scene_rate_hz);
  scratch_.in_force =
      pipeline::emptyBus(resolved_->cartesian() ? COMPLY_COMMAND_CARTESIAN : COMPLY_COMMAND_JOINT);
  thread_ = std::thread([this] { run(); });
}

LiveView::~LiveView() {
  running_ = false;
  thread_.join();
}

void LiveView::run() {
  while (running_.load()) {
    viewing_.store(server_.clients() > 0, std::memory_order_relaxed);
    if (cycles_.update()) {
      publishCycle(cycles_.read());
      scene_->publish(cycles_.read());
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

void LiveView::publishCycle(const ViewedCycle& cycle) {
  const std::int64_t time_ns = cycle.state.wall.nanoseconds();
  if (server_.wants(state_channel_)) {
    transport::encodeCdr(stateMessage(cycle.state, *resolved_), cycle_bytes_);
    server_.publish(state_channel_, time_ns, cycle_bytes_);
  }
  if (server_.wants(cycle_channel_)) {
    const auto message = std::visit(
        [&](const auto& bus) {
          using Bus = std::decay_t<decltype(bus)>;
          using Command = std::conditional_t<std::is_same_v<Bus, comply_cartesian_command>,
                                             CartesianCommand, JointCommand>;
          return cycleRecordMessage<Command>(cycle.state, bus, cycle.compute_s,
                                             cycle.start_lateness_s, *resolved_);
        },
        cycle.in_force);
    transport::encodeCdr(message, cycle_bytes_);
    server_.publish(cycle_channel_, time_ns, cycle_bytes_);
  }
}

template <typename Message>
void LiveView::publishMessage(viewer::ChannelId channel, const Message& message,
                              transport::Stamp time) {
  if (!server_.wants(channel)) {
    return;
  }
  const std::lock_guard lock(encode_mutex_);
  transport::encodeCdr(message, encode_bytes_);
  server_.publish(channel, time.nanoseconds(), encode_bytes_);
}

template <typename Message>
void LiveView::received(const Message& message, transport::Stamp received_at) {
  if constexpr (std::is_same_v<Message, transport::CartesianChunkMessage>) {
    scene_->setPath(message.chunk, received_at);
  }
  publishMessage(senders_.of<Message>(), message, received_at);
}

template void LiveView::received(const transport::CartesianCommandMessage&, transport::Stamp);
template void LiveView::received(const transport::JointCommandMessage&, transport::Stamp);
template void LiveView::received(const transport::CartesianChunkMessage&, transport::Stamp);
template void LiveView::received(const transport::JointChunkMessage&, transport::Stamp);
template void LiveView::received(const transport::RequestMessage&, transport::Stamp);

void LiveView::outcome(const transport::CommandOutcomeMessage& message) {
  publishMessage(
      outcome_channel_, message,
      message.outcome == transport::Outcome::kApplied ? message.applied : message.received);
}

void LiveView::diagnostics(const transport::DiagnosticsMessage& message) {
  publishMessage(diagnostics_channel_, message, message.header.stamp);
}

bool LiveView::waitForViewer(double timeout_s, const std::atomic<bool>* stop) const {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (server_.clients() == 0) {
    if (std::chrono::steady_clock::now() >= deadline || (stop != nullptr && stop->load())) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

}  // namespace comply::host
