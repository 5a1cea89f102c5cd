#pragma once
// A controller's ROS parameters back into comply's controller file. ROS flattens the nested YAML
// of a controller file (`validation: {max_position_jump_m: 0.1}`) into dotted parameter names
// (`validation.max_position_jump_m`); rebuilding the file lets comply's own parser read it, with
// the same checks and the same messages as `comply sim --config`, so one file works in both.

#include <rclcpp/parameter.hpp>
#include <string>
#include <vector>

namespace comply_ros2_control {

/// True for parameters the ROS side owns (declared by ros2_control or by these controllers), which
/// are not comply options and would be refused as unknown keys.
bool isRosSideParameter(const std::string& name);

/// The comply controller file (`<controller_name>: ros__parameters: ...`) holding `parameters`,
/// nested at each '.' of their names; ROS-side parameters are left out.
std::string controllerFileText(const std::string& controller_name,
                               const std::vector<rclcpp::Parameter>& parameters);

}  // namespace comply_ros2_control
