#pragma once
// comply's wrapper as a ros2_control controller, for either command kind.
//
//   on_init        comply's options are declared as parameters (comply_parameters.hpp)
//   on_configure   the controller's parameters are comply's controller file
//                  (comply_parameters.hpp): robot, plugin, model, gains and limits are resolved
//                  once; errors name the parameter and the controller stays unconfigured
//   on_activate    the reference is seeded from the measured state (comply's activation)
//   update         one comply cycle: state interfaces -> wrapper -> command interfaces, then the
//                  cycle's state sample into a triple buffer; no allocation, no lock, no exception
//   on_deactivate  the wrapper stops; the last torque stays on the interfaces until the
//                  hardware or the next controller takes them
//
// The command interfaces claimed follow the file's output.mode (docs/output-modes.md): torque
// <joint>/effort; position <joint>/position; velocity <joint>/velocity; joint_pd <joint>/position,
// /velocity, /effort (tau_ff), /stiffness (kp) and /damping (kd).
//
// Topics (relative to the controller's node, /<controller name>/...):
//   ~/cartesian_command or ~/joint_command   comply_msgs command, through comply's command gate as
//                  in `comply run`: strictly newer stamps, one publisher at a time, every command
//                  applied (with the cycle that took it) or rejected with a reason
//   ~/cartesian_chunk or ~/joint_chunk   comply_msgs timed chunk (docs/chunks.md), through the
//                  same gate; waypoint times on the node's clock
//   ~/state        comply_msgs/ControllerState at state_publish_rate_hz (default 100 Hz): the
//                  newest cycle's, built as `comply run` builds it (comply::host::stateMessage)
//   ~/diagnostics  comply_msgs/Diagnostics at diagnostics_publish_rate_hz (default 10 Hz), built
//                  as `comply run` builds it (comply::host::diagnosticsMessage): the compute time
//                  of update() and its start lateness as histograms, the overruns, and the outcome
//                  of every command received since the previous message
//   ~/request      comply_msgs/Request, as `comply run` answers it, each answered by an outcome on
//                  ~/diagnostics: probe (what comply's clients send first), reset, tare; activate
//                  and deactivate are refused, naming the controller manager's command; reset and
//                  tare held to the publisher rule
//   ~/committed_request -> ~/committed   comply_msgs/CommittedRequest and its answer, Committed:
//                  what the controller will execute at the times asked for if no new command
//                  arrives (docs/policies.md), from `comply run`'s code (comply/host/
//                  committed_answers.hpp), on the node's clock, the answer naming its sender
//   ~/reset_fault  std_srvs/Trigger: leave FAULT
//   ~/tare         std_srvs/Trigger: the wrist force/torque reading becomes its zero (refused
//                  while no force-torque state interface has given a reading)
// The state and the diagnostics are built off the real-time thread, in the executor's timers, and
// copied into comply_msgs by the message tables (comply/transport/message_copy.hpp).
//
// A wrist force/torque sensor (docs/contact-wrench.md), by parameters outside comply's file:
//   force_torque_sensor.name             its state interfaces are <name>/force.x ... /torque.z
//   force_torque_sensor.interface_names  or six full names (force x y z, torque x y z)
//   force_torque_sensor.frame            tcp (default: the sensor's axes, aligned with the TCP,
//                                        turned with it every cycle) or base
// A recording (docs/recording.md), by the parameter `record` (a file path; "" none): the cycle
// record of every update() (/<name>/cycle, with the gains and task frame in force), every
// command's outcome, the chunks' timing and the diagnostics, written to MCAP as
// `comply run --record` writes them, by a writer thread of its own; update() only copies the
// cycle into a lane, never waits (a full lane drops the record and counts it in ~/diagnostics).
//
// The live view (docs/live-view.md), by the parameter `foxglove` ("[ADDRESS:]PORT"; "" none): the
// Foxglove WebSocket server of `comply run --foxglove`, fed by update() wait-free, with the cycle,
// state, commands, outcomes, the robot and its stiffness drawn in 3D.
//
// The command and state topics and types are those of `comply run`, so comply's Python client
// and `comply send` / `comply echo` talk to either host.

#include <controller_interface/controller_interface.hpp>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/trigger.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "comply/core/actuator_command.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/host/committed_answers.hpp"
#include "comply/host/diagnostics_message.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/live_view.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply_msgs/msg/cartesian_chunk.hpp"
#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/committed.hpp"
#include "comply_msgs/msg/committed_request.hpp"
#include "comply_msgs/msg/controller_state.hpp"
#include "comply_msgs/msg/diagnostics.hpp"
#include "comply_msgs/msg/joint_chunk.hpp"
#include "comply_msgs/msg/joint_command.hpp"
#include "comply_msgs/msg/request.hpp"
#include "comply_ros2_control/writer_identity.hpp"

namespace comply_ros2_control {

/// The command and chunk topics of a command kind, and their messages.
template <typename Command>
struct CommandTopic {
  static constexpr bool kCartesian = std::is_same_v<Command, comply::CartesianCommand>;
  using Message = std::conditional_t<kCartesian, comply_msgs::msg::CartesianCommand,
                                     comply_msgs::msg::JointCommand>;
  using ChunkMessage = std::conditional_t<kCartesian, comply_msgs::msg::CartesianChunk,
                                          comply_msgs::msg::JointChunk>;
  static constexpr const char* kName = kCartesian ? "~/cartesian_command" : "~/joint_command";
  static constexpr const char* kChunkName = kCartesian ? "~/cartesian_chunk" : "~/joint_chunk";
};

template <typename Command>
class ComplyController : public controller_interface::ControllerInterface {
 public:
  using CallbackReturn = controller_interface::CallbackReturn;
  using CommandMessage = typename CommandTopic<Command>::Message;
  using ChunkMessage = typename CommandTopic<Command>::ChunkMessage;

  CallbackReturn on_init() override;
  [[nodiscard]] controller_interface::InterfaceConfiguration command_interface_configuration()
      const override;
  [[nodiscard]] controller_interface::InterfaceConfiguration state_interface_configuration()
      const override;
  CallbackReturn on_configure(const rclcpp_lifecycle::State& previous) override;
  CallbackReturn on_activate(const rclcpp_lifecycle::State& previous) override;
  CallbackReturn on_deactivate(const rclcpp_lifecycle::State& previous) override;
  CallbackReturn on_cleanup(const rclcpp_lifecycle::State& previous) override;
  controller_interface::return_type update(const rclcpp::Time& time,
                                           const rclcpp::Duration& period) override;

 private:
  void resolve();
  void createEndpoints();
  bool mapInterfaces();
  /// The force_torque_sensor.* parameters into sensor_interfaces_; throws on a bad one.
  void resolveSensor();
  /// The `record` parameter's recording (none when it is empty); throws naming a bad path.
  void openRecording();
  /// The `foxglove` parameter's live view (none when it is empty); throws naming a bad address.
  void openView();
  /// A message as received, into the recording and the live view (either may be absent).
  template <typename Message>
  void noteReceived(const Message& message);
  void readState() noexcept;
  void onCommand(const CommandMessage& message, const rclcpp::MessageInfo& info);
  void onChunk(const ChunkMessage& message, const rclcpp::MessageInfo& info);
  /// A command or chunk with `header`, taken by the subscription `writers` identifies the senders
  /// of, through the gate; `submit` hands it to the wrapper.
  template <typename Header, typename Submit>
  void offerToGate(const Header& header, const rclcpp::MessageInfo& info, WriterIdentity& writers,
                   const std::string& malformed, Submit&& submit);
  /// Releases the command topics from every writer that left since the last call, and drops a
  /// chunk of its that waits for its start, as `comply run` does. Under the endpoints mutex.
  void releaseDeparted();
  /// The same for `publisher`, the writer of the message just offered, if it had already left
  /// when releaseDeparted() last listed the writers (it sent, then exited).
  void releaseIfGone(std::uint64_t publisher);
  void releaseWriter(std::uint64_t publisher);
  void onResetFault(std_srvs::srv::Trigger::Response& response);
  void onRequest(const comply_msgs::msg::Request& message, const rclcpp::MessageInfo& info);
  void onCommittedRequest(const comply_msgs::msg::CommittedRequest& message,
                          const rclcpp::MessageInfo& info);
  /// What `request` (not a probe) does here; "" when carried out, else why not.
  std::string carryOut(std::uint8_t request);
  /// After the cycle, on the real-time thread: timing and the state sample. No allocation.
  void afterCycle(const rclcpp::Time& time, bool wrote, double start_s) noexcept;
  /// Everything configure made, in the order its users need it gone (timers first).
  void release();
  void publishState();
  void publishDiagnostics();

  std::shared_ptr<const comply::pipeline::ResolvedController> resolved_;
  std::unique_ptr<comply::pipeline::Wrapper<Command>> wrapper_;
  std::unique_ptr<comply::host::HostRecording> recording_;  ///< the `record` parameter's; or none
  std::unique_ptr<comply::host::LiveView> view_;            ///< the `foxglove` parameter's; or none
  std::vector<std::string> joints_;
  // Index of each joint's interface in state_interfaces_ / command_interfaces_, in joints_ order:
  // ros2_control loans them in its own order.
  std::vector<std::size_t> position_index_, velocity_index_, effort_index_;
  // The command interfaces of joint i, field k at i * command_fields_.size() + k.
  std::vector<std::size_t> command_index_;
  std::vector<comply::JointVector comply::ActuatorCommand::*> command_fields_;
  // The wrist sensor's six state interfaces (empty: none) and their index in state_interfaces_.
  std::vector<std::string> sensor_interfaces_;
  std::vector<std::size_t> sensor_index_;
  bool sensor_in_tcp_ = true;
  comply::JointState state_;
  comply::ActuatorCommand command_;
  std::uint64_t cycle_ = 0;
  double nominal_period_s_ = 0.001;
  double previous_start_s_ = 0.0;  ///< steady clock [s] at the previous update(); 0: none yet
  // Every command passes it; update() tells it which cycle took them (wait-free), the
  // diagnostics timer settles and publishes their outcomes.
  std::unique_ptr<comply::pipeline::CommandGate> gate_;

  // The executor's callbacks (timers, subscriptions, services) and the lifecycle transitions may
  // run on different threads of a multi-threaded executor: they hold this while they use what
  // configure made. update() never takes it (the controller manager runs it only while active).
  std::mutex endpoints_mutex_;
  // Timing of update() (written by the real-time thread, read by the diagnostics timer) and the
  // newest cycle's state sample (update() fills the scratch and hands it over wait-free).
  std::unique_ptr<comply::host::LoopCounters> loop_;
  std::unique_ptr<comply::host::StateSampler<Command>> sampler_;
  comply::host::StateSample sample_;
  std::unique_ptr<comply::TripleBuffer<comply::host::StateSample>> samples_;

  typename rclcpp::Subscription<CommandMessage>::SharedPtr command_subscription_;
  typename rclcpp::Subscription<ChunkMessage>::SharedPtr chunk_subscription_;
  std::optional<WriterIdentity> command_writers_;
  std::optional<WriterIdentity> chunk_writers_;
  rclcpp::Subscription<comply_msgs::msg::Request>::SharedPtr request_subscription_;
  std::optional<WriterIdentity> request_writers_;
  rclcpp::Subscription<comply_msgs::msg::CommittedRequest>::SharedPtr committed_subscription_;
  std::optional<WriterIdentity> committed_writers_;
  rclcpp::Publisher<comply_msgs::msg::Committed>::SharedPtr committed_publisher_;
  std::unique_ptr<comply::host::CommittedAnswers<Command>> committed_;
  comply_msgs::msg::Committed committed_message_;  ///< reused: its lists keep their room
  std::vector<std::uint64_t> departed_;
  rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr reset_service_;
  rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr tare_service_;
  rclcpp::TimerBase::SharedPtr state_timer_;
  rclcpp::TimerBase::SharedPtr diagnostics_timer_;
  rclcpp::Publisher<comply_msgs::msg::ControllerState>::SharedPtr state_publisher_;
  rclcpp::Publisher<comply_msgs::msg::Diagnostics>::SharedPtr diagnostics_publisher_;
};

class JointController final : public ComplyController<comply::JointCommand> {};
class CartesianController final : public ComplyController<comply::CartesianCommand> {};

extern template class ComplyController<comply::JointCommand>;
extern template class ComplyController<comply::CartesianCommand>;

}  // namespace comply_ros2_control
