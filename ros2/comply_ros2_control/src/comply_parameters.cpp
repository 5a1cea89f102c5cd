#include "comply_ros2_control/comply_parameters.hpp"

#include <array>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

namespace comply_ros2_control {
namespace {

using comply::pipeline::OptionDeclaration;
using comply::pipeline::ParameterType;

rclcpp::ParameterType rosType(ParameterType type) {
  switch (type) {
    case ParameterType::kBool:
      return rclcpp::ParameterType::PARAMETER_BOOL;
    case ParameterType::kString:
      return rclcpp::ParameterType::PARAMETER_STRING;
    case ParameterType::kDoubleList:
      return rclcpp::ParameterType::PARAMETER_DOUBLE_ARRAY;
    case ParameterType::kDouble:
      break;
  }
  return rclcpp::ParameterType::PARAMETER_DOUBLE;
}

rclcpp::ParameterValue rosValue(const comply::pipeline::ParameterValue& value) {
  return std::visit(
      [](const auto& held) {
        if constexpr (std::is_same_v<std::decay_t<decltype(held)>, std::monostate>) {
          return rclcpp::ParameterValue();
        } else {
          return rclcpp::ParameterValue(held);
        }
      },
      value);
}

comply::pipeline::ParameterValue complyValue(const rclcpp::Parameter& parameter) {
  using rclcpp::ParameterType;
  switch (parameter.get_type()) {
    case ParameterType::PARAMETER_BOOL:
      return parameter.as_bool();
    case ParameterType::PARAMETER_INTEGER:
      return std::int64_t{parameter.as_int()};
    case ParameterType::PARAMETER_DOUBLE:
      return parameter.as_double();
    case ParameterType::PARAMETER_STRING:
      return parameter.as_string();
    case ParameterType::PARAMETER_BOOL_ARRAY:
      return parameter.as_bool_array();
    case ParameterType::PARAMETER_INTEGER_ARRAY:
      return parameter.as_integer_array();
    case ParameterType::PARAMETER_DOUBLE_ARRAY:
      return parameter.as_double_array();
    case ParameterType::PARAMETER_STRING_ARRAY:
      return parameter.as_string_array();
    default:
      return {};  // not set, byte arrays: nothing comply reads
  }
}

rcl_interfaces::msg::ParameterDescriptor descriptorOf(const OptionDeclaration& option) {
  rcl_interfaces::msg::ParameterDescriptor descriptor;
  descriptor.name = option.name;
  descriptor.type = rosType(option.type);
  descriptor.description = option.description;
  descriptor.additional_constraints = option.constraint;
  if (option.type == ParameterType::kDouble) {
    // Inclusive at both ends in ROS; an excluded bound is comply's parser's to refuse. Finite
    // ends: rclcpp lets every value through a range that ends at infinity.
    rcl_interfaces::msg::FloatingPointRange range;
    range.from_value = option.min;
    range.to_value = option.max;
    range.step = 0.0;
    descriptor.floating_point_range.push_back(range);
  }
  return descriptor;
}

}  // namespace

void declareOptions(rclcpp_lifecycle::LifecycleNode& node) {
  const auto& overrides = node.get_node_parameters_interface()->get_parameter_overrides();
  for (const OptionDeclaration& option : comply::pipeline::optionDeclarations()) {
    std::optional<rclcpp::ParameterValue> given;
    if (const auto found = overrides.find(option.name); found != overrides.end()) {
      given = found->second;
    }
    if (node.has_parameter(option.name)) {
      // Declared from the overrides, dynamically typed and without a descriptor: again, with one.
      given = node.get_parameter(option.name).get_parameter_value();
      node.undeclare_parameter(option.name);
    }
    rcl_interfaces::msg::ParameterDescriptor descriptor = descriptorOf(option);
    const rclcpp::ParameterValue default_value = rosValue(option.default_value);
    descriptor.dynamic_typing =
        default_value.get_type() == rclcpp::ParameterType::PARAMETER_NOT_SET ||
        (given && given->get_type() != rosType(option.type));
    try {
      if (given) {
        node.declare_parameter(option.name, *given, descriptor, /*ignore_override=*/true);
      } else {
        node.declare_parameter(option.name, default_value, descriptor);
      }
    } catch (const std::exception& error) {
      throw std::runtime_error("parameter " + option.name + " " + option.constraint + " (" +
                               error.what() + ")");
    }
  }
}

bool isRosSideParameter(const std::string& name) {
  // ros2_control's own (update_rate; is_async and thread_priority in newer releases) and this
  // controller's.
  static constexpr std::array<std::string_view, 9> kRosSide = {"use_sim_time",
                                                               "update_rate",
                                                               "is_async",
                                                               "thread_priority",
                                                               "robot_description",
                                                               "state_publish_rate_hz",
                                                               "diagnostics_publish_rate_hz",
                                                               "record",
                                                               "foxglove"};
  for (const auto ros_side : kRosSide) {
    if (name == ros_side) {
      return true;
    }
  }
  return name.rfind("qos_overrides.", 0) == 0 || name.rfind("force_torque_sensor.", 0) == 0;
}

std::vector<comply::pipeline::FlatParameter> complyParameters(
    const std::vector<rclcpp::Parameter>& parameters) {
  std::vector<comply::pipeline::FlatParameter> flat;
  for (const auto& parameter : parameters) {
    if (!isRosSideParameter(parameter.get_name())) {
      flat.push_back({parameter.get_name(), complyValue(parameter)});
    }
  }
  return flat;
}

}  // namespace comply_ros2_control
