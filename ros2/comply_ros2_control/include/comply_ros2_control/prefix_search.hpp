#pragma once
// Plugin and robot names also resolve in the comply prefix this package was built against. comply's
// own search ($COMPLY_PLUGIN_PATH, $COMPLY_ROBOT_PATH, then the folders next to the binary holding
// comply's code) looks next to this package's library under ROS 2, not in comply's prefix.

#include <string>

namespace comply_ros2_control {

/// `plugin` as comply's search finds it, else the matching file of comply's prefix, else unchanged
/// (so that comply's own error lists where it looked).
std::string pluginInPrefix(const std::string& plugin);
/// The same for a robot name (a folder holding robot.yaml).
std::string robotInPrefix(const std::string& robot);

}  // namespace comply_ros2_control
