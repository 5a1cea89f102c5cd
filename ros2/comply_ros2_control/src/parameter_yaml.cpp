#include "comply_ros2_control/parameter_yaml.hpp"

#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string_view>

namespace comply_ros2_control {
namespace {

struct Node {
  std::string value;  // YAML text of a leaf; empty for a map
  std::map<std::string, std::unique_ptr<Node>> children;
};

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

std::string number(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.17g", value);  // round-trips a double exactly
  return text.data();
}

template <typename T, typename Format>
std::string list(const std::vector<T>& values, Format format) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i == 0 ? "" : ", ") + format(values[i]);
  }
  return out + "]";
}

std::string yamlValue(const rclcpp::Parameter& parameter) {
  using rclcpp::ParameterType;
  switch (parameter.get_type()) {
    case ParameterType::PARAMETER_BOOL:
      return parameter.as_bool() ? "true" : "false";
    case ParameterType::PARAMETER_INTEGER:
      return std::to_string(parameter.as_int());
    case ParameterType::PARAMETER_DOUBLE:
      return number(parameter.as_double());
    case ParameterType::PARAMETER_STRING:
      return quoted(parameter.as_string());
    case ParameterType::PARAMETER_BOOL_ARRAY:
      return list(parameter.as_bool_array(),
                  [](bool b) { return std::string(b ? "true" : "false"); });
    case ParameterType::PARAMETER_INTEGER_ARRAY:
      return list(parameter.as_integer_array(), [](std::int64_t i) { return std::to_string(i); });
    case ParameterType::PARAMETER_DOUBLE_ARRAY:
      return list(parameter.as_double_array(), number);
    case ParameterType::PARAMETER_STRING_ARRAY:
      return list(parameter.as_string_array(), quoted);
    default:
      return {};  // not set, byte arrays: nothing comply reads
  }
}

void insert(Node& root, const std::string& dotted_name, std::string value) {
  Node* node = &root;
  std::stringstream parts(dotted_name);
  std::string part;
  while (std::getline(parts, part, '.')) {
    auto& child = node->children[part];
    if (!child) {
      child = std::make_unique<Node>();
    }
    node = child.get();
  }
  node->value = std::move(value);
}

void write(const Node& node, int indent, std::string& out) {
  for (const auto& [key, child] : node.children) {
    out += std::string(static_cast<std::size_t>(indent), ' ') + key + ":";
    if (child->children.empty()) {
      out += " " + child->value + "\n";
    } else {
      out += "\n";
      write(*child, indent + 2, out);
    }
  }
}

}  // namespace

bool isRosSideParameter(const std::string& name) {
  static constexpr std::array<std::string_view, 5> kRosSide = {
      "use_sim_time", "update_rate", "robot_description", "state_publish_rate_hz",
      "diagnostics_publish_rate_hz"};
  for (const auto ros_side : kRosSide) {
    if (name == ros_side) {
      return true;
    }
  }
  return name.rfind("qos_overrides.", 0) == 0 || name.rfind("force_torque_sensor.", 0) == 0;
}

std::string controllerFileText(const std::string& controller_name,
                               const std::vector<rclcpp::Parameter>& parameters) {
  Node root;
  for (const auto& parameter : parameters) {
    std::string value = yamlValue(parameter);
    if (!value.empty() && !isRosSideParameter(parameter.get_name())) {
      insert(root, parameter.get_name(), std::move(value));
    }
  }
  std::string out = controller_name + ":\n  ros__parameters:\n";
  write(root, 4, out);
  return out;
}

}  // namespace comply_ros2_control
