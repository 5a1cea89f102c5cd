#pragma once
// What every host records (`--record FILE`) and on which channel of the MCAP file:
//
//   /<name>/cycle              comply_msgs/CycleRecord   every control cycle
//   /<name>/cartesian_command  comply_msgs/CartesianCommand  every command as received
//   /<name>/joint_command      comply_msgs/JointCommand      every command as received
//   /<name>/cartesian_chunk    comply_msgs/CartesianChunk    every chunk as received
//   /<name>/joint_chunk        comply_msgs/JointChunk        every chunk as received
//   /<name>/request            comply_msgs/Request       every request as received
//   /<name>/outcome            comply_msgs/CommandOutcome   one per command
//   /<name>/chunk_timing       comply_msgs/ChunkTiming   one per chunk: its outcome's chunk entry
//   /<name>/diagnostics        comply_msgs/Diagnostics   as published
//   /<name>/camera/<camera>    sensor_msgs/CompressedImage  every frame a simulated camera took
//
// Messages are the CDR bytes of the wire. Each group of channels has its own lane with one
// producer: cycle() is called by the control thread and costs a copy of the state sample (about
// 1 KB) and, when it changed, of the command in force (CycleRecorder);
// command() and request() by the thread that takes commands, outcome() and diagnostics() by the
// one that publishes (these encode where they are called: they are off the control thread).
//
// A full lane (the disk busy, the writer behind) is the host's to decide
// (HostRecordingOptions::when_full): `comply run` drops and counts, its control thread never
// waits; `comply sim` and comply.Sim have no deadline and wait, so their recordings are whole.

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "comply/host/sender_channels.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/record/recorder.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/compressed_image.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

/// A channel of `Message` on `topic`, its schema the ROS 2 definition of the message's type (one
/// schema per type however many channels use it). `encoder` turns a record into the message's
/// bytes; none: the records are those bytes.
template <typename Message>
std::uint16_t addMessageChannel(record::Recorder& recorder, const std::string& topic,
                                record::RecordEncoder encoder = {}) {
  const std::string_view type = transport::rosTypeName<Message>();
  const std::uint16_t schema =
      recorder.addSchema(type, "ros2msg", transport::ros2MessageDefinition(type));
  return recorder.addChannel(schema, topic, std::move(encoder));
}

/// The cycle record of `state` with the command the law used, `in_force`, and the cycle's timing:
/// what a recording and the live view carry on `/<name>/cycle` (allocates: off the control thread).
template <typename Command>
transport::CycleRecordMessage cycleRecordMessage(const StateSample& state,
                                                 const pipeline::BusOf<Command>& in_force,
                                                 double compute_s, double start_lateness_s,
                                                 const pipeline::ResolvedController& resolved);

/// A recording's channels of what a sender writes (sender_channels.hpp), as the hosts and the
/// Python client record them.
class SenderChannels : public SenderChannelIds<std::uint16_t> {
 public:
  SenderChannels() = default;
  SenderChannels(record::Recorder& recorder, const std::string& prefix);
};

/// The control lane's size. A cycle is ~1 KB in it (the command in force travels only when it
/// changed), so 1 MiB holds about a second of cycles at 1 kHz should the writer stall (a slow
/// disk), and stays in the control core's L2 cache: a 16 MiB lane made every push miss it.
inline constexpr std::size_t kControlLaneBytes = std::size_t{1} << 20;

/// How a host records, besides where.
struct HostRecordingOptions {
  /// A full lane: record::WhenFull::kDrop for a host with a deadline (comply run),
  /// record::WhenFull::kWait for one without (comply sim, comply.Sim). Every host names its own.
  record::WhenFull when_full;
  std::size_t control_lane_bytes = kControlLaneBytes;
  /// The writer's sleep when it found nothing to write (record::RecorderOptions).
  double writer_period_s = 0.005;
  /// The cameras whose frames image() records, a channel each (none: no camera lane).
  std::vector<std::string> cameras;
};

/// One cycle as the recording's control lane holds it.
struct RecordedCycle {
  StateSample state;
  double compute_s = 0.0;
  double start_lateness_s = 0.0;
};

/// The control thread's side of a recording: a RecordedCycle every cycle, and the command the
/// law used (Controller::lawBus()) only when it changed (a new command, a ramp step), on a lane
/// record of its own that the writer encodes every later cycle with. A cycle record is then
/// half the size, and so is what a push costs.
template <typename Command>
class CycleRecorder {
 public:
  CycleRecorder(record::RecordLane& lane, std::uint16_t cycle_channel,
                std::uint16_t in_force_channel)
      : lane_(lane), cycle_channel_(cycle_channel), in_force_channel_(in_force_channel) {}

  /// No allocation; wait-free with WhenFull::kDrop, where a full lane drops the record (and a
  /// dropped command in force is pushed again with the next cycle); with WhenFull::kWait a full
  /// lane waits for the writer.
  void push(const StateSample& state, const pipeline::BusOf<Command>& in_force, double compute_s,
            double start_lateness_s) noexcept {
    const std::int64_t time_ns = state.wall.nanoseconds();
    if ((!pushed_any_ || std::memcmp(&in_force, &last_, sizeof last_) != 0) &&
        lane_.push(in_force_channel_, time_ns, in_force)) {
      last_ = in_force;
      pushed_any_ = true;
    }
    lane_.emplace<RecordedCycle>(cycle_channel_, time_ns, state, compute_s, start_lateness_s);
  }

 private:
  record::RecordLane& lane_;
  std::uint16_t cycle_channel_;
  std::uint16_t in_force_channel_;
  pipeline::BusOf<Command> last_{};
  bool pushed_any_ = false;
};

class HostRecording {
 public:
  /// Creates `path` (throws record::McapError naming it, or its missing folder: none is made)
  /// and starts the writer thread. `metadata`: what the file says about the run besides the
  /// counts (robot, controller, ...).
  HostRecording(const std::string& path,
                std::shared_ptr<const pipeline::ResolvedController> resolved,
                const std::string& name, record::StringMap metadata, HostRecordingOptions options);
  ~HostRecording();
  HostRecording(const HostRecording&) = delete;
  HostRecording& operator=(const HostRecording&) = delete;

  /// The control thread, after a cycle: `state` (filled for this cycle), the command the law
  /// used and the cycle's timing. No allocation; a full lane drops the record (wait-free) or
  /// waits for room, by HostRecordingOptions::when_full.
  template <typename Command>
  void cycle(const StateSample& state, const pipeline::BusOf<Command>& in_force, double compute_s,
             double start_lateness_s) noexcept {
    // get_if: the recorder's kind is the controller's, but std::get may throw.
    if (auto* cycles = std::get_if<CycleRecorder<Command>>(&cycles_)) {
      cycles->push(state, in_force, compute_s, start_lateness_s);
    }
  }

  // The command thread: a command or chunk of either kind, or a request, as received.
  template <typename Message>
  void received(const Message& message, transport::Stamp received_at);
  // The publishing thread. An outcome's chunk timing record goes on chunk_timing too, at its
  // takeover (or, never taken over, at the outcome's time).
  void outcome(const transport::CommandOutcomeMessage& message);
  void diagnostics(const transport::DiagnosticsMessage& message);
  /// The thread that renders: a frame of camera `camera` (its index in
  /// HostRecordingOptions::cameras), logged at the time its header is stamped with. A frame
  /// larger than half the camera lane is dropped and counted.
  void image(std::size_t camera, const transport::CompressedImageMessage& message);

  /// Drains, writes the counts and closes the file; idempotent.
  void stop();
  [[nodiscard]] record::RecorderStats stats() const { return recorder_.stats(); }
  [[nodiscard]] const std::string& path() const noexcept { return recorder_.path(); }

 private:
  std::shared_ptr<const pipeline::ResolvedController> resolved_;
  record::Recorder recorder_;
  pipeline::CommandBus in_force_;  // the writer thread's: the one cycles are encoded with
  SenderChannels senders_;
  std::uint16_t outcome_channel_ = 0;
  std::uint16_t chunk_timing_channel_ = 0;
  std::uint16_t diagnostics_channel_ = 0;
  std::vector<std::uint16_t> camera_channels_;
  record::RecordLane& control_;
  record::RecordLane& intake_;
  record::RecordLane& publisher_;
  record::RecordLane* cameras_ = nullptr;  // only with cameras
  std::variant<std::monostate, CycleRecorder<CartesianCommand>, CycleRecorder<JointCommand>>
      cycles_;
  std::vector<std::uint8_t> intake_bytes_;     // the command thread's scratch
  std::vector<std::uint8_t> publisher_bytes_;  // the publishing thread's scratch
  std::vector<std::uint8_t> camera_bytes_;     // the rendering thread's scratch
};

}  // namespace comply::host
