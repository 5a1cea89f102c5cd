#pragma once
// What a host serves to Foxglove (`--foxglove [ADDRESS:]PORT`): a Foxglove WebSocket server
// (viewer/foxglove_server.hpp) with the host's channels, in the wire's CDR with their ROS 2
// definitions as a recording has them, and what a 3D panel draws:
//
//   /<name>/state              comply_msgs/ControllerState   at most state_rate_hz
//   /<name>/cycle              comply_msgs/CycleRecord       at most state_rate_hz
//   /<name>/diagnostics        comply_msgs/Diagnostics       as published
//   /<name>/outcome            comply_msgs/CommandOutcome    one per command
//   /<name>/cartesian_command ... /<name>/request            every command, chunk and request
//                                                             as received
//   /robot_description         std_msgs/String               the URDF, latched
//   /tf                        foxglove.FrameTransforms      the links, /<name>/task_frame,
//                                                             /<name>/reference; scene_rate_hz
//   /<name>/markers            foxglove.SceneUpdate          stiffness ellipsoid, contact force,
//                                                             the chunk's path; scene_rate_hz
//
// The control thread's part is cycle(): while no viewer is connected it returns at once; while
// one is, it copies the cycle into a triple buffer. A thread of the view's own takes the newest
// cycle from there, encodes and publishes it: the control cycle never encodes, allocates or waits
// for a client.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "comply/core/triple_buffer.hpp"
#include "comply/host/sender_channels.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/transport/messages.hpp"
#include "comply/viewer/foxglove_server.hpp"

namespace comply::host {

struct LiveViewOptions {
  std::string address = "127.0.0.1";  ///< loopback unless said
  std::uint16_t port = 8765;          ///< 0: any free port
  double state_rate_hz = 1000.0;      ///< the state and cycle channels at most
  double scene_rate_hz = 30.0;        ///< transforms and markers
  /// Per client and channel (viewer::ServerOptions::channel_queue_bytes).
  std::size_t channel_queue_bytes = std::size_t{1} << 20;
};

/// "PORT" or "ADDRESS:PORT" (an IPv6 address in brackets) into options' address and port. Throws
/// std::invalid_argument saying what is wrong.
LiveViewOptions parseViewAddress(std::string_view text);

/// "live view: N messages sent to viewers, M dropped for slow viewers (/topic k, ...)".
std::string describeViewStats(const std::vector<viewer::ChannelStats>& stats);

/// One cycle as the view's triple buffer holds it.
struct ViewedCycle {
  StateSample state;
  pipeline::CommandBus in_force;
  double compute_s = 0.0;
  double start_lateness_s = 0.0;
};

class LiveView {
 public:
  /// Starts the server (throws viewer::ViewerError naming the address it cannot listen on) and
  /// the view's thread. `name`: the host's, the channels' prefix.
  LiveView(const LiveViewOptions& options,
           std::shared_ptr<const pipeline::ResolvedController> resolved, const std::string& name);
  ~LiveView();
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  /// The control thread, after a cycle. No allocation, wait-free; nothing without a viewer.
  template <typename Command>
  void cycle(const StateSample& state, const pipeline::BusOf<Command>& in_force, double compute_s,
             double start_lateness_s) noexcept {
    if (!viewing_.load(std::memory_order_relaxed)) {
      return;
    }
    scratch_.state = state;
    scratch_.in_force = in_force;
    scratch_.compute_s = compute_s;
    scratch_.start_lateness_s = start_lateness_s;
    cycles_.publishFromSoleWriter(scratch_);
  }

  // Off the control thread: a command, chunk or request as received (a Cartesian chunk's
  // waypoints become the path drawn), an outcome, the diagnostics as published.
  template <typename Message>
  void received(const Message& message, transport::Stamp received_at);
  void outcome(const transport::CommandOutcomeMessage& message);
  void diagnostics(const transport::DiagnosticsMessage& message);

  /// A viewer is connected (as of the view thread's last look, within a millisecond or so).
  [[nodiscard]] bool viewing() const noexcept { return viewing_.load(std::memory_order_relaxed); }
  /// The same flag, for a clock that paces while it is set.
  [[nodiscard]] const std::atomic<bool>& viewingFlag() const noexcept { return viewing_; }
  /// Waits up to `timeout_s` for a viewer (or until `stop` is set); true when one came.
  bool waitForViewer(double timeout_s, const std::atomic<bool>* stop = nullptr) const;
  [[nodiscard]] std::string url() const { return server_.url(); }
  [[nodiscard]] std::vector<viewer::ChannelStats> stats() const { return server_.stats(); }

 private:
  class Scene;
  void run();
  void publishCycle(const ViewedCycle& cycle);
  template <typename Message>
  void publishMessage(viewer::ChannelId channel, const Message& message, transport::Stamp time);

  std::shared_ptr<const pipeline::ResolvedController> resolved_;
  viewer::FoxgloveServer server_;
  std::unique_ptr<Scene> scene_;
  viewer::ChannelId state_channel_ = 0;
  viewer::ChannelId cycle_channel_ = 0;
  viewer::ChannelId diagnostics_channel_ = 0;
  viewer::ChannelId outcome_channel_ = 0;
  SenderChannelIds<viewer::ChannelId> senders_;

  std::atomic<bool> viewing_{false};
  ViewedCycle scratch_;  // the control thread's
  TripleBuffer<ViewedCycle> cycles_;
  std::mutex encode_mutex_;  // the threads that publish received messages share a scratch
  std::vector<std::uint8_t> encode_bytes_;
  std::vector<std::uint8_t> cycle_bytes_;  // the view thread's
  std::atomic<bool> running_{true};
  std::thread thread_;
};

}  // namespace comply::host
