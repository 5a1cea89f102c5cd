#include "comply_ros2_control/prefix_search.hpp"

#include <filesystem>

#include "comply/model/robot_description.hpp"
#include "comply/plugin/loader.hpp"

namespace comply_ros2_control {
namespace {

bool isName(const std::string& name_or_path) {
  return name_or_path.find('/') == std::string::npos &&
         !std::filesystem::path(name_or_path).has_extension();
}

}  // namespace

std::string pluginInPrefix(const std::string& plugin) {
  if (!isName(plugin)) {
    return plugin;
  }
  try {
    return comply::plugin::resolvePlugin(plugin).string();
  } catch (const comply::plugin::PluginError&) {
    const auto in_prefix =
        std::filesystem::path(COMPLY_PREFIX_PLUGIN_DIR) / ("libcomply_" + plugin + ".so");
    return std::filesystem::is_regular_file(in_prefix) ? in_prefix.string() : plugin;
  }
}

std::string robotInPrefix(const std::string& robot) {
  if (!isName(robot)) {
    return robot;
  }
  for (const auto& folder : comply::model::robotSearchPath()) {
    if (std::filesystem::is_regular_file(folder / robot / "robot.yaml")) {
      return robot;
    }
  }
  const auto in_prefix = std::filesystem::path(COMPLY_PREFIX_ROBOTS_DIR) / robot;
  return std::filesystem::is_regular_file(in_prefix / "robot.yaml") ? in_prefix.string() : robot;
}

}  // namespace comply_ros2_control
