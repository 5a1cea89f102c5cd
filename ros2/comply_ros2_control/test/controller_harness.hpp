#pragma once
// A comply controller in a ros2_control harness (loaned interfaces over plain doubles, as the
// controller manager hands them out), configured from comply's own controller file given as a ROS
// parameters file; and the harness with ROS 2 senders and a listener of its topics.

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <lifecycle_msgs/msg/state.hpp>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/controller_state.hpp"
#include "comply_msgs/msg/diagnostics.hpp"
#include "comply_ros2_control/comply_controller.hpp"

namespace comply_ros2_control {

namespace hi = hardware_interface;

inline const std::string kConfig = std::string(COMPLY_CONFIG_DIR) + "/sim/cartesian_impedance.yaml";

inline std::string fileText(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

class ControllerHarness : public ::testing::Test {
 protected:
  void SetUp() override {
    rclcpp::init(0, nullptr);
    std::vector<std::string> arguments{"--ros-args", "--params-file", kConfig};
    if (!sensor_interfaces_.empty()) {
      arguments.insert(arguments.end(), {"-p", sensor_parameter_});
    }
    for (const std::string& parameter : extra_parameters_) {
      arguments.insert(arguments.end(), {"-p", parameter});
    }
    if (output_mode_ != "torque") {
      arguments.insert(arguments.end(), {"-p", "output.mode:=" + output_mode_});
    }
    const auto options = rclcpp::NodeOptions()
                             .allow_undeclared_parameters(true)
                             .automatically_declare_parameters_from_overrides(true)
                             .arguments(arguments);
    ASSERT_EQ(controller_.init("cartesian_impedance", "", options),
              controller_interface::return_type::OK);
    ASSERT_EQ(controller_.configure().id(), lifecycle_msgs::msg::State::PRIMARY_STATE_INACTIVE);
    const auto robot = comply::model::loadRobotDescription("fr3");
    dof_ = robot.joints.size();
    values_.resize(3 * dof_);
    command_values_.resize(commandKinds().size() * dof_);
    for (std::size_t i = 0; i < dof_; ++i) {
      values_[3 * i] = robot.home[i];
      state_interfaces_.emplace_back(robot.joints[i], "position", &values_[3 * i]);
      state_interfaces_.emplace_back(robot.joints[i], "velocity", &values_[3 * i + 1]);
      state_interfaces_.emplace_back(robot.joints[i], "effort", &values_[3 * i + 2]);
      for (std::size_t k = 0; k < commandKinds().size(); ++k) {
        command_interfaces_.emplace_back(robot.joints[i], commandKinds()[k],
                                         &command_values_[i * commandKinds().size() + k]);
      }
    }
    for (std::size_t k = 0; k < sensor_interfaces_.size(); ++k) {
      const std::string& name = sensor_interfaces_[k];
      const std::size_t slash = name.find('/');
      state_interfaces_.emplace_back(name.substr(0, slash), name.substr(slash + 1), &wrench_[k]);
    }
    std::vector<hi::LoanedStateInterface> loaned_states;
    std::vector<hi::LoanedCommandInterface> loaned_commands;
    // Loaned in an order of ros2_control's choosing: reversed here, the controller must map.
    for (auto it = state_interfaces_.rbegin(); it != state_interfaces_.rend(); ++it) {
      loaned_states.emplace_back(*it);
    }
    for (auto& command : command_interfaces_) {
      loaned_commands.emplace_back(command);
    }
    controller_.assign_interfaces(std::move(loaned_commands), std::move(loaned_states));
    ASSERT_EQ(controller_.get_node()->activate().id(),
              lifecycle_msgs::msg::State::PRIMARY_STATE_ACTIVE);
  }
  void TearDown() override {
    controller_.get_node()->deactivate();
    controller_.release_interfaces();
    rclcpp::shutdown();
  }

  /// The command interfaces of a joint, as the controller claims them in its output.mode.
  std::vector<std::string> commandKinds() const {
    if (output_mode_ == "joint_pd") {
      return {"position", "velocity", "effort", "stiffness", "damping"};
    }
    if (output_mode_ == "position" || output_mode_ == "velocity") {
      return {output_mode_};
    }
    return {"effort"};
  }
  /// Command interface `kind` of `joint` (index into commandKinds()).
  double command(std::size_t joint, std::size_t kind) const {
    return command_values_[joint * commandKinds().size() + kind];
  }
  double torque(std::size_t joint) const { return command(joint, 0); }
  comply::JointState jointState() const {
    auto state = comply::JointState::zero(static_cast<int>(dof_));
    for (std::size_t i = 0; i < dof_; ++i) {
      state.position[static_cast<Eigen::Index>(i)] = values_[3 * i];
    }
    return state;
  }

  /// A wrist sensor "ft" on ros2_control's force-torque interfaces (ft/force.x ... ft/torque.z).
  void withSensor() {
    sensor_parameter_ = "force_torque_sensor.name:=ft";
    sensor_interfaces_ = {"ft/force.x",  "ft/force.y",  "ft/force.z",
                          "ft/torque.x", "ft/torque.y", "ft/torque.z"};
  }

  CartesianController controller_;
  /// The wrist sensor's parameter ("name:=value") and the six state interfaces the hardware
  /// exports for it (force x y z, torque x y z); none without.
  std::string sensor_parameter_;
  std::vector<std::string> sensor_interfaces_;
  std::vector<std::string> extra_parameters_;  ///< more "-p name:=value" for the controller
  std::string output_mode_ = "torque";  ///< output.mode, and the command interfaces it claims
  std::array<double, 6> wrench_{};      ///< its reading: force x y z [N], torque x y z [N m]
  std::size_t dof_ = 0;
  std::vector<double> values_;          // per joint: position, velocity, effort
  std::vector<double> command_values_;  // per joint: commandKinds()
  std::vector<hi::StateInterface> state_interfaces_;
  std::vector<hi::CommandInterface> command_interfaces_;
};

using comply_msgs::msg::CartesianCommand;
using comply_msgs::msg::CommandOutcome;
using comply_msgs::msg::ControllerState;
using comply_msgs::msg::Diagnostics;

/// Two senders and a listener of the controller's topics, spun with it between cycles.
class TopicHarness : public ControllerHarness {
 protected:
  void SetUp() override {
    ControllerHarness::SetUp();
    listener_ = std::make_shared<rclcpp::Node>("listener");
    // A context of its own is a DDS participant of its own: to comply's gate, as another process
    // (the listener shares the controller's). Its publishers need no spinning.
    second_context_ = std::make_shared<rclcpp::Context>();
    second_context_->init(0, nullptr);
    second_sender_ = std::make_shared<rclcpp::Node>("second_sender",
                                                    rclcpp::NodeOptions().context(second_context_));
    const std::string topic = "/cartesian_impedance/cartesian_command";
    sender_a_ = listener_->create_publisher<CartesianCommand>(topic, rclcpp::QoS(1000).reliable());
    sender_b_ =
        second_sender_->create_publisher<CartesianCommand>(topic, rclcpp::QoS(1000).reliable());
    state_ = listener_->create_subscription<ControllerState>(
        "/cartesian_impedance/state", rclcpp::SensorDataQoS(),
        [this](const ControllerState& state) { states_.push_back(state); });
    diagnostics_ = listener_->create_subscription<Diagnostics>(
        "/cartesian_impedance/diagnostics", rclcpp::QoS(100).reliable(),
        [this](const Diagnostics& diagnostics) {
          diagnostics_received_.push_back(diagnostics);
          outcomes_.insert(outcomes_.end(), diagnostics.outcomes.begin(),
                           diagnostics.outcomes.end());
        });
    executor_ = std::make_unique<rclcpp::executors::SingleThreadedExecutor>();
    executor_->add_node(controller_.get_node()->get_node_base_interface());
    executor_->add_node(listener_);
    ASSERT_TRUE(runUntil([this] {
      return sender_a_->get_subscription_count() > 0 && sender_b_->get_subscription_count() > 0 &&
             !states_.empty() && !diagnostics_received_.empty();
    })) << "the controller's topics were not discovered";
  }
  void TearDown() override {
    executor_.reset();
    state_.reset();
    diagnostics_.reset();
    sender_a_.reset();
    sender_b_.reset();
    listener_.reset();
    second_sender_.reset();
    second_context_->shutdown("test done");
    second_context_.reset();
    ControllerHarness::TearDown();
  }

  /// Cycles on the node's clock, the executor spun between them, until `done` or 10 s.
  template <typename Done>
  bool runUntil(Done&& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      // A joint moving a little: a stream that never changes is a frozen sensor (FAULT).
      values_[1] = 1e-3 * static_cast<double>(cycles_ % 7);
      controller_.update(controller_.get_node()->now(), rclcpp::Duration(0, 1'000'000));
      ++cycles_;
      executor_->spin_some(std::chrono::milliseconds(1));
      if (done()) {
        return true;
      }
    }
    return false;
  }

  /// The measured TCP pose as a command from `stamp`.
  CartesianCommand holdCommand(const rclcpp::Time& stamp) const {
    CartesianCommand command;
    command.header.stamp = stamp;
    command.fields = static_cast<std::uint32_t>(comply::CommandField::kPosition);
    command.position = states_.back().tcp_position;
    command.orientation = states_.back().tcp_orientation;
    return command;
  }

  /// The outcome of the command from `stamp`, once the diagnostics brought it.
  std::optional<CommandOutcome> outcomeOf(const rclcpp::Time& stamp, std::size_t nth = 0) {
    runUntil([&] {
      std::size_t seen = 0;
      for (const CommandOutcome& outcome : outcomes_) {
        seen += rclcpp::Time(outcome.stamp) == stamp ? 1 : 0;
      }
      return seen > nth;
    });
    for (const CommandOutcome& outcome : outcomes_) {
      if (rclcpp::Time(outcome.stamp) == stamp && nth-- == 0) {
        return outcome;
      }
    }
    return std::nullopt;
  }

  std::unique_ptr<rclcpp::executors::SingleThreadedExecutor> executor_;  // after rclcpp::init
  std::shared_ptr<rclcpp::Node> listener_;
  std::shared_ptr<rclcpp::Context> second_context_;
  std::shared_ptr<rclcpp::Node> second_sender_;
  rclcpp::Publisher<CartesianCommand>::SharedPtr sender_a_;
  rclcpp::Publisher<CartesianCommand>::SharedPtr sender_b_;
  rclcpp::Subscription<ControllerState>::SharedPtr state_;
  rclcpp::Subscription<Diagnostics>::SharedPtr diagnostics_;
  std::vector<ControllerState> states_;
  std::vector<Diagnostics> diagnostics_received_;
  std::vector<CommandOutcome> outcomes_;
  std::uint64_t cycles_ = 0;
};

class SensorTopicHarness : public TopicHarness {
 protected:
  SensorTopicHarness() { withSensor(); }
};

}  // namespace comply_ros2_control
