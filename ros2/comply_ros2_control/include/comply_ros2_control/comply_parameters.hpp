#pragma once
// comply's options as the controller's ROS parameters. ROS flattens the nested YAML of a
// controller file (`validation: {max_position_jump_m: 0.1}`) into dotted parameter names
// (`validation.max_position_jump_m`). on_init declares every option with the type, default,
// range and description of comply's option table, so `ros2 param describe` documents them;
// on_configure hands the parameters to comply's parser (pipeline/config_parameters.hpp), with
// the same checks and messages as `comply sim --config`, so one file works in both.

#include <rclcpp/parameter.hpp>
#include <rclcpp_lifecycle/lifecycle_node.hpp>
#include <string>
#include <vector>

#include "comply/pipeline/config_parameters.hpp"

namespace comply_ros2_control {

/// Declares every option of comply's table on `node`. A parameter the controller file set (and
/// rclcpp declared from its overrides) keeps its value and gains the descriptor; one of another
/// type than the option's (an integer for a number, one number for a per-joint list) is declared
/// dynamically typed, for comply's parser to read. Throws std::runtime_error naming the
/// parameter when rclcpp refuses a value (outside the option's range).
void declareOptions(rclcpp_lifecycle::LifecycleNode& node);

/// True for parameters the ROS side owns (declared by ros2_control or by these controllers), which
/// are not comply options and would be refused as unknown keys.
bool isRosSideParameter(const std::string& name);

/// The node's parameters that are comply's (every one but the ROS side's), as comply reads them.
std::vector<comply::pipeline::FlatParameter> complyParameters(
    const std::vector<rclcpp::Parameter>& parameters);

}  // namespace comply_ros2_control
