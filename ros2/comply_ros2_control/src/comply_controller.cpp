#include "comply_ros2_control/comply_controller.hpp"

#include <cstddef>
#include <ctime>
#include <exception>
#include <stdexcept>
#include <type_traits>

#include "comply/core/clock.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/config_parameters.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/transport/message_copy.hpp"
#include "comply_ros2_control/command_interfaces.hpp"
#include "comply_ros2_control/comply_parameters.hpp"
#include "comply_ros2_control/message_conversion.hpp"
#include "comply_ros2_control/prefix_search.hpp"

namespace comply_ros2_control {
namespace {

using controller_interface::CallbackReturn;
using controller_interface::interface_configuration_type;
using controller_interface::InterfaceConfiguration;

constexpr const char* kStateRate = "state_publish_rate_hz";
constexpr const char* kDiagnosticsRate = "diagnostics_publish_rate_hz";
constexpr const char* kRobotDescription = "robot_description";
// The wrist force/torque sensor's state interfaces: "<name>/force.x" ... "<name>/torque.z" (the
// ros2_control ForceTorqueSensor names), or six full names; its frame: tcp (the sensor's axes,
// aligned with the TCP) or base.
constexpr const char* kSensorName = "force_torque_sensor.name";
constexpr const char* kSensorInterfaces = "force_torque_sensor.interface_names";
constexpr const char* kSensorFrame = "force_torque_sensor.frame";
constexpr const char* kRecord = "record";      ///< an MCAP file to record to ("": none)
constexpr const char* kFoxglove = "foxglove";  ///< the live view's [ADDRESS:]PORT ("": none)
constexpr std::size_t kCommandDepth = 1000;    ///< commands waiting for the executor, at most

// The index in `interfaces` of "<joint>/<kind>"; throws naming the missing one.
template <typename Loaned>
std::size_t indexOf(const std::vector<Loaned>& interfaces, const std::string& joint,
                    const std::string& kind) {
  for (std::size_t i = 0; i < interfaces.size(); ++i) {
    if (interfaces[i].get_prefix_name() == joint && interfaces[i].get_interface_name() == kind) {
      return i;
    }
  }
  throw std::runtime_error("no interface " + joint + "/" + kind + " was loaned");
}

// The index in `interfaces` of the interface named `name` ("<prefix>/<interface>").
template <typename Loaned>
std::size_t indexOfName(const std::vector<Loaned>& interfaces, const std::string& name) {
  for (std::size_t i = 0; i < interfaces.size(); ++i) {
    if (interfaces[i].get_name() == name) {
      return i;
    }
  }
  throw std::runtime_error("no interface " + name + " was loaned (" + kSensorName + ")");
}

}  // namespace

template <typename Command>
CallbackReturn ComplyController<Command>::on_init() {
  // comply's options with their types, defaults, ranges and descriptions (comply_parameters.hpp);
  // names, plugin parameters and the initial block arrive from the controller file as written.
  try {
    declareOptions(*get_node());
  } catch (const std::exception& error) {
    RCLCPP_ERROR(get_node()->get_logger(), "refused: %s", error.what());
    return CallbackReturn::ERROR;
  }
  auto_declare<double>(kStateRate, 100.0);
  auto_declare<double>(kDiagnosticsRate, 10.0);
  auto_declare<std::string>(kRobotDescription, "");
  auto_declare<std::string>(kSensorName, "");
  auto_declare<std::vector<std::string>>(kSensorInterfaces, {});
  auto_declare<std::string>(kSensorFrame, "tcp");
  auto_declare<std::string>(kRecord, "");
  auto_declare<std::string>(kFoxglove, "");
  return CallbackReturn::SUCCESS;
}

template <typename Command>
InterfaceConfiguration ComplyController<Command>::command_interface_configuration() const {
  InterfaceConfiguration configuration{interface_configuration_type::INDIVIDUAL, {}};
  const comply::OutputMode mode = wrapper_ ? wrapper_->outputMode() : comply::OutputMode::kTorque;
  for (const auto& joint : joints_) {
    for (const CommandInterface& interface : commandInterfacesOf(mode)) {
      configuration.names.push_back(joint + "/" + interface.kind);
    }
  }
  return configuration;
}

template <typename Command>
InterfaceConfiguration ComplyController<Command>::state_interface_configuration() const {
  InterfaceConfiguration configuration{interface_configuration_type::INDIVIDUAL, {}};
  for (const auto& joint : joints_) {
    for (const char* kind : {"/position", "/velocity", "/effort"}) {
      configuration.names.push_back(joint + kind);
    }
  }
  configuration.names.insert(configuration.names.end(), sensor_interfaces_.begin(),
                             sensor_interfaces_.end());
  return configuration;
}

template <typename Command>
void ComplyController<Command>::resolve() {
  const auto node = get_node();
  const std::string name = node->get_name();
  const auto parameters = node->get_parameters(node->list_parameters({}, 0).names);
  const std::string source = "the parameters of controller '" + name + "'";
  comply::pipeline::WrapperConfig config =
      comply::pipeline::parseWrapperParameters(complyParameters(parameters), source, name);
  config.plugin = pluginInPrefix(config.plugin);
  config.robot = robotInPrefix(config.robot);
  auto robot = std::make_shared<comply::model::RobotDescription>(
      comply::model::loadRobotDescription(config.robot));
  robot->urdf_xml = node->get_parameter(kRobotDescription).as_string();
  comply::pipeline::completeForRobot(config, robot);
  resolved_ = comply::pipeline::resolveController(config);
  wrapper_ = std::make_unique<comply::pipeline::Wrapper<Command>>(resolved_);
  gate_ = std::make_unique<comply::pipeline::CommandGate>(
      comply::pipeline::gateOptions(config, std::is_same_v<Command, comply::CartesianCommand>));
  joints_ = config.joints;
  resolveSensor();
}

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
CallbackReturn ComplyController<Command>::on_configure(const rclcpp_lifecycle::State&) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  try {
    resolve();
    createEndpoints();
  } catch (const std::exception& error) {
    RCLCPP_ERROR(get_node()->get_logger(), "cannot configure: %s", error.what());
    release();
    // FAILURE, not ERROR: the controller stays unconfigured, and rclcpp_lifecycle does not run
    // its error processing (whose log, "Error occurred while doing error handling.", misleads).
    return CallbackReturn::FAILURE;
  }
  const int dof = wrapper_->dof();
  command_.resize(dof);
  RCLCPP_INFO(get_node()->get_logger(), "configured: plugin %s on %d joints (%s)",
              wrapper_->controller().resolved().plugin->path().c_str(), dof,
              wrapper_->controller().resolved().robot.name.c_str());
  return CallbackReturn::SUCCESS;
}

template <typename Command>
void ComplyController<Command>::resolveSensor() {
  const auto node = get_node();
  const std::string name = node->get_parameter(kSensorName).as_string();
  const std::vector<std::string> names = node->get_parameter(kSensorInterfaces).as_string_array();
  const std::string frame = node->get_parameter(kSensorFrame).as_string();
  if (frame != "tcp" && frame != "base") {
    throw std::runtime_error(std::string(kSensorFrame) + " must be tcp or base, not '" + frame +
                             "'");
  }
  if (!names.empty() && names.size() != 6) {
    throw std::runtime_error(std::string(kSensorInterfaces) +
                             " names six interfaces (force x y z, torque x y z), not " +
                             std::to_string(names.size()));
  }
  sensor_interfaces_ = names;
  if (names.empty() && !name.empty()) {
    for (const char* axis : {"force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z"}) {
      sensor_interfaces_.push_back(name + "/" + axis);
    }
  }
  sensor_in_tcp_ = frame == "tcp";
}

template <typename Command>
bool ComplyController<Command>::mapInterfaces() {
  const std::size_t dof = joints_.size();
  const std::vector<CommandInterface> claimed = commandInterfacesOf(wrapper_->outputMode());
  position_index_.resize(dof);
  velocity_index_.resize(dof);
  effort_index_.resize(dof);
  command_index_.clear();
  command_fields_.clear();
  for (const CommandInterface& interface : claimed) {
    command_fields_.push_back(interface.field);
  }
  for (std::size_t i = 0; i < dof; ++i) {
    position_index_[i] = indexOf(state_interfaces_, joints_[i], "position");
    velocity_index_[i] = indexOf(state_interfaces_, joints_[i], "velocity");
    effort_index_[i] = indexOf(state_interfaces_, joints_[i], "effort");
    for (const CommandInterface& interface : claimed) {
      command_index_.push_back(indexOf(command_interfaces_, joints_[i], interface.kind));
    }
  }
  sensor_index_.clear();
  for (const std::string& name : sensor_interfaces_) {
    sensor_index_.push_back(indexOfName(state_interfaces_, name));
  }
  return true;
}

template <typename Command>
void ComplyController<Command>::readState() noexcept {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const auto joint = static_cast<Eigen::Index>(i);
    state_.position[joint] = state_interfaces_[position_index_[i]].get_value();
    state_.velocity[joint] = state_interfaces_[velocity_index_[i]].get_value();
    state_.effort[joint] = state_interfaces_[effort_index_[i]].get_value();
  }
  if (sensor_index_.size() == 6) {
    for (std::size_t k = 0; k < 6; ++k) {
      state_.wrench[static_cast<Eigen::Index>(k)] = state_interfaces_[sensor_index_[k]].get_value();
    }
    state_.wrench_valid = state_.wrench.allFinite();
    state_.wrench_in_tcp = sensor_in_tcp_;
  }
}

template <typename Command>
CallbackReturn ComplyController<Command>::on_activate(const rclcpp_lifecycle::State&) {
  try {
    mapInterfaces();
    state_ = comply::JointState::zero(static_cast<int>(joints_.size()));
    readState();
    wrapper_->activate(state_);
  } catch (const std::exception& error) {
    RCLCPP_ERROR(get_node()->get_logger(), "cannot activate: %s", error.what());
    return CallbackReturn::FAILURE;  // stays inactive (see on_configure)
  }
  cycle_ = 0;
  previous_start_s_ = 0.0;
  return CallbackReturn::SUCCESS;
}

template <typename Command>
CallbackReturn ComplyController<Command>::on_deactivate(const rclcpp_lifecycle::State&) {
  if (wrapper_) {
    wrapper_->deactivate();
  }
  return CallbackReturn::SUCCESS;
}

template <typename Command>
CallbackReturn ComplyController<Command>::on_cleanup(const rclcpp_lifecycle::State&) {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  release();
  return CallbackReturn::SUCCESS;
}

template <typename Command>
void ComplyController<Command>::release() {
  state_timer_.reset();
  diagnostics_timer_.reset();
  reset_service_.reset();
  tare_service_.reset();
  command_subscription_.reset();
  command_writers_.reset();
  chunk_writers_.reset();
  request_writers_.reset();
  request_subscription_.reset();
  committed_writers_.reset();
  committed_subscription_.reset();
  committed_publisher_.reset();
  committed_.reset();
  chunk_subscription_.reset();
  diagnostics_publisher_.reset();
  state_publisher_.reset();
  view_.reset();  // its thread reads the wrapper's resolved controller: gone first
  if (recording_) {
    recording_->stop();
    const comply::record::RecorderStats stats = recording_->stats();
    RCLCPP_INFO(get_node()->get_logger(), "recorded %llu messages to %s, dropped %llu%s%s",
                static_cast<unsigned long long>(stats.written), recording_->path().c_str(),
                static_cast<unsigned long long>(stats.dropped),
                stats.error.empty() ? "" : "; stopped early: ", stats.error.c_str());
    recording_.reset();
  }
  samples_.reset();
  sampler_.reset();
  loop_.reset();
  wrapper_.reset();
  resolved_.reset();
  gate_.reset();
  joints_.clear();
}

template <typename Command>
controller_interface::return_type ComplyController<Command>::update(
    const rclcpp::Time& time, const rclcpp::Duration& period) {
  const double start_s = comply::hardware::monotonicSeconds();
  readState();
  const double period_s = period.seconds() > 0.0 ? period.seconds() : nominal_period_s_;
  // The cycle in the file's output.mode: a torque, a per-joint PD split or an admittance step.
  const bool wrote = wrapper_->cycle(state_, period_s, command_);
  if (wrote) {
    const std::size_t fields = command_fields_.size();
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      for (std::size_t k = 0; k < fields; ++k) {
        command_interfaces_[command_index_[i * fields + k]].set_value(
            (command_.*command_fields_[k])[static_cast<Eigen::Index>(i)]);
      }
    }
  }
  // The chunks' timing records before the cycle, so that its outcomes carry their own; the
  // node's clock is the host's.
  const comply::pipeline::Controller& controller = wrapper_->controller();
  for (const comply::pipeline::ChunkTiming& timing : controller.chunks().events()) {
    gate_->noteChunk(cycle_, timing, controller.time(), time.nanoseconds());
  }
  gate_->noteCycle(cycle_, wrapper_->controller().idInForce(),
                   [&time] { return time.nanoseconds(); });
  afterCycle(time, wrote, start_s);
  return controller_interface::return_type::OK;
}

template <typename Command>
void ComplyController<Command>::afterCycle(const rclcpp::Time& time, bool wrote,
                                           double start_s) noexcept {
  comply::hardware::CycleRecord record;
  record.index = cycle_++;
  record.period_s = nominal_period_s_;
  record.wrote = wrote;
  record.state = &state_;
  record.torque = std::span<const double>(command_.effort.data(),
                                          static_cast<std::size_t>(command_.effort.size()));
  record.command = &command_;
  sampler_->fill(record, state_, comply::transport::Stamp::fromNanoseconds(time.nanoseconds()),
                 sample_);
  samples_->publishFromSoleWriter(sample_);
  // The controller manager schedules update(): its lateness is how much later than one nominal
  // period after the previous start this one started, on the steady clock (ROS time may be
  // simulated, and the manager's `period` is its own loop's).
  const double lateness_s =
      previous_start_s_ > 0.0 ? start_s - previous_start_s_ - nominal_period_s_ : 0.0;
  if (previous_start_s_ > 0.0) {
    comply::host::LoopCounters::count(loop_->lateness, lateness_s);
  }
  previous_start_s_ = start_s;
  const double compute_s = comply::hardware::monotonicSeconds() - start_s;
  if (recording_ || view_) {
    // get_if: the bus holds the controller's kind, and std::get may throw.
    if (const auto* in_force =
            std::get_if<comply::pipeline::BusOf<Command>>(&wrapper_->controller().lawBus())) {
      if (recording_) {
        recording_->cycle<Command>(sample_, *in_force, compute_s, lateness_s);
      }
      if (view_) {
        view_->cycle<Command>(sample_, *in_force, compute_s, lateness_s);
      }
    }
  }
  loop_->countCycle(compute_s, compute_s > nominal_period_s_);
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
  releaseDeparted(0);
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
  releaseDeparted(writer.publisher);
}

template <typename Command>
void ComplyController<Command>::releaseDeparted(std::uint64_t just_heard) {
  departed_.clear();
  if (command_writers_->namesSenders() && chunk_writers_->namesSenders()) {
    command_writers_->noteDepartures(departed_);
    chunk_writers_->noteDepartures(departed_);
    if (just_heard != 0 && !command_writers_->isMatched(just_heard) &&
        !chunk_writers_->isMatched(just_heard)) {
      departed_.push_back(just_heard);
    }
  } else if (gate_->publisher() != 0 && command_subscription_->get_publisher_count() == 0 &&
             chunk_subscription_->get_publisher_count() == 0) {
    departed_.push_back(gate_->publisher());  // no sender named: gone when no one publishes
  }
  for (const std::uint64_t publisher : departed_) {
    if (const std::uint64_t chunk = gate_->releasePublisher(publisher); chunk != 0) {
      wrapper_->dropWaitingChunk(chunk);
    }
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
  releaseDeparted(0);
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

template <typename Command>
void ComplyController<Command>::publishDiagnostics() {
  const std::lock_guard<std::mutex> lock(endpoints_mutex_);
  if (!wrapper_) {
    return;
  }
  releaseDeparted(0);
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

template class ComplyController<comply::JointCommand>;
template class ComplyController<comply::CartesianCommand>;

}  // namespace comply_ros2_control
