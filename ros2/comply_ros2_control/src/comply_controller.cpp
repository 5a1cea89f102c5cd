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
#include "comply_ros2_control/command_interfaces.hpp"
#include "comply_ros2_control/comply_parameters.hpp"
#include "comply_ros2_control/prefix_search.hpp"
#include "controller_parameter_names.hpp"

namespace comply_ros2_control {
namespace {

using controller_interface::CallbackReturn;
using controller_interface::interface_configuration_type;
using controller_interface::InterfaceConfiguration;
using namespace parameter_names;  // NOLINT(google-build-using-namespace): the package's own names

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

template class ComplyController<comply::JointCommand>;
template class ComplyController<comply::CartesianCommand>;

}  // namespace comply_ros2_control
