// The channels of a host's recording and the encoding of its records (see host_recording.hpp).

#include "comply/host/host_recording.hpp"

#include <cstring>

#include "comply/schema/schema.hpp"
#include "comply/transport/cdr.hpp"

namespace comply::host {
namespace {

// The command and publishing lanes see a few hundred records a second.
constexpr std::size_t kSideLaneBytes = std::size_t{4} << 20;
// Camera frames are PNGs of tens to hundreds of KB, a few per policy step: room for a second of
// them at 30 fps should the disk stall.
constexpr std::size_t kCameraLaneBytes = std::size_t{32} << 20;

record::RecorderOptions recorderOptions(const std::string& path, const HostRecordingOptions& host) {
  record::RecorderOptions options;
  options.path = path;  // its folder must exist: a mistyped path makes no folders
  options.writer_period_s = host.writer_period_s;
  options.when_full = host.when_full;
  return options;
}

template <typename Command>
void encodeCycle(std::span<const std::uint8_t> raw, const pipeline::BusOf<Command>& in_force,
                 const pipeline::ResolvedController& resolved, std::vector<std::uint8_t>& out) {
  const auto& cycle = record::recordAs<RecordedCycle>(raw);
  transport::encodeCdr(cycleRecordMessage<Command>(cycle.state, in_force, cycle.compute_s,
                                                   cycle.start_lateness_s, resolved),
                       out);
}

template <typename Message>
void push(record::RecordLane& lane, std::uint16_t channel, const Message& message,
          transport::Stamp time, std::vector<std::uint8_t>& scratch) {
  transport::encodeCdr(message, scratch);
  lane.push(channel, time.nanoseconds(), scratch.data(), scratch.size());
}

}  // namespace

template <typename Command>
transport::CycleRecordMessage cycleRecordMessage(const StateSample& state,
                                                 const pipeline::BusOf<Command>& in_force,
                                                 double compute_s, double start_lateness_s,
                                                 const pipeline::ResolvedController& resolved) {
  transport::CycleRecordMessage message;
  message.state = stateMessage(state, resolved);
  message.compute_time_s = compute_s;
  message.start_lateness_s = start_lateness_s;
  const transport::Header header{transport::Stamp::fromNanoseconds(state.reference.stamp_ns),
                                 resolved.robot.base_frame};
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    message.cartesian_in_force.push_back({header, schema::fromBus(in_force)});
  } else {
    message.joint_in_force.push_back({header, schema::fromBus(in_force)});
  }
  return message;
}

template transport::CycleRecordMessage cycleRecordMessage<CartesianCommand>(
    const StateSample&, const pipeline::BusOf<CartesianCommand>&, double, double,
    const pipeline::ResolvedController&);
template transport::CycleRecordMessage cycleRecordMessage<JointCommand>(
    const StateSample&, const pipeline::BusOf<JointCommand>&, double, double,
    const pipeline::ResolvedController&);

SenderChannels::SenderChannels(record::Recorder& recorder, const std::string& prefix)
    : SenderChannelIds(prefix, [&recorder](const std::string& topic, auto message) {
        return addMessageChannel<typename decltype(message)::type>(recorder, topic);
      }) {}

HostRecording::HostRecording(const std::string& path,
                             std::shared_ptr<const pipeline::ResolvedController> resolved,
                             const std::string& name, record::StringMap metadata,
                             HostRecordingOptions options)
    : resolved_(std::move(resolved)),
      recorder_(recorderOptions(path, options)),
      control_(recorder_.addLane("control", options.control_lane_bytes)),
      intake_(recorder_.addLane("commands", kSideLaneBytes)),
      publisher_(recorder_.addLane("publisher", kSideLaneBytes)) {
  const std::string prefix = "/" + name + "/";
  const pipeline::ResolvedController& controller = *resolved_;
  const auto channels = [&]<typename Command>() {
    using Bus = pipeline::BusOf<Command>;
    in_force_ = Bus{};
    // The writer thread keeps the command in force, and encodes each cycle with it.
    const std::uint16_t in_force = recorder_.addInternal([this](std::span<const std::uint8_t> raw) {
      std::memcpy(&std::get<Bus>(in_force_), raw.data(), sizeof(Bus));
    });
    const std::uint16_t cycle = addMessageChannel<transport::CycleRecordMessage>(
        recorder_, prefix + "cycle",
        [this, &controller](std::span<const std::uint8_t> raw, auto& out) {
          encodeCycle<Command>(raw, std::get<Bus>(in_force_), controller, out);
        });
    cycles_.emplace<CycleRecorder<Command>>(control_, cycle, in_force);
  };
  if (controller.cartesian()) {
    channels.template operator()<CartesianCommand>();
  } else {
    channels.template operator()<JointCommand>();
  }
  // Both kinds' topics: a command of the other kind is refused, and recorded as received.
  senders_ = SenderChannels(recorder_, prefix);
  outcome_channel_ =
      addMessageChannel<transport::CommandOutcomeMessage>(recorder_, prefix + "outcome");
  chunk_timing_channel_ =
      addMessageChannel<transport::ChunkTimingMessage>(recorder_, prefix + "chunk_timing");
  diagnostics_channel_ =
      addMessageChannel<transport::DiagnosticsMessage>(recorder_, prefix + "diagnostics");
  if (!options.cameras.empty()) {
    cameras_ = &recorder_.addLane("cameras", kCameraLaneBytes);
    const std::uint16_t schema =
        recorder_.addSchema(transport::kCompressedImageType, "ros2msg",
                            transport::ros2MessageDefinition(transport::kCompressedImageType));
    for (const std::string& camera : options.cameras) {
      camera_channels_.push_back(recorder_.addChannel(schema, prefix + "camera/" + camera, {}));
    }
  }
  metadata["robot"] = controller.robot.name;
  metadata["plugin"] = controller.config.plugin;
  metadata["dof"] = std::to_string(controller.config.dof);
  metadata["base_frame"] = controller.robot.base_frame;
  recorder_.addMetadata("comply_run", std::move(metadata));
  recorder_.start();
}

HostRecording::~HostRecording() {
  stop();
}

template <typename Message>
void HostRecording::received(const Message& message, transport::Stamp received_at) {
  push(intake_, senders_.of<Message>(), message, received_at, intake_bytes_);
}

template void HostRecording::received(const transport::CartesianCommandMessage&, transport::Stamp);
template void HostRecording::received(const transport::JointCommandMessage&, transport::Stamp);
template void HostRecording::received(const transport::CartesianChunkMessage&, transport::Stamp);
template void HostRecording::received(const transport::JointChunkMessage&, transport::Stamp);
template void HostRecording::received(const transport::RequestMessage&, transport::Stamp);

void HostRecording::outcome(const transport::CommandOutcomeMessage& message) {
  const transport::Stamp time =
      message.outcome == transport::Outcome::kApplied ? message.applied : message.received;
  push(publisher_, outcome_channel_, message, time, publisher_bytes_);
  for (const transport::ChunkTimingMessage& timing : message.chunk) {
    push(publisher_, chunk_timing_channel_, timing,
         timing.takeover != transport::Stamp{} ? timing.takeover : time, publisher_bytes_);
  }
}

void HostRecording::diagnostics(const transport::DiagnosticsMessage& message) {
  push(publisher_, diagnostics_channel_, message, message.header.stamp, publisher_bytes_);
}

void HostRecording::image(std::size_t camera, const transport::CompressedImageMessage& message) {
  if (cameras_ == nullptr || camera >= camera_channels_.size()) {
    return;
  }
  transport::encodeCdr(message, camera_bytes_);
  cameras_->push(camera_channels_[camera], message.header.stamp.nanoseconds(), camera_bytes_.data(),
                 camera_bytes_.size());
}

void HostRecording::stop() {
  recorder_.stop();
}

}  // namespace comply::host
