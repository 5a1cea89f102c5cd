#include "controller_setup.hpp"

#include <yaml-cpp/emitter.h>

#include <stdexcept>

namespace comply::app {

pipeline::WrapperConfig controllerConfig(const std::string& robot, const std::string& plugin,
                                         const std::string& config_file) {
  if (!config_file.empty()) {
    pipeline::WrapperConfig config = pipeline::loadWrapperConfig(config_file);
    if ((!robot.empty() && robot != config.robot) || (!plugin.empty() && plugin != config.plugin)) {
      throw std::runtime_error(config_file + " configures robot '" + config.robot +
                               "' and plugin '" + config.plugin +
                               "'; drop --robot/--plugin or edit the file");
    }
    return config;
  }
  if (robot.empty() || plugin.empty()) {
    throw std::runtime_error("without --config, both --robot and --plugin are needed");
  }
  // Through the YAML reader, so defaults come from one place. Quoted: paths may hold any text.
  YAML::Emitter yaml;
  yaml << YAML::BeginMap << YAML::Key << "comply_controller" << YAML::Value << YAML::BeginMap
       << YAML::Key << "ros__parameters" << YAML::Value << YAML::BeginMap << YAML::Key << "plugin"
       << YAML::Value << YAML::DoubleQuoted << plugin << YAML::Key << "robot" << YAML::Value
       << YAML::DoubleQuoted << robot << YAML::EndMap << YAML::EndMap << YAML::EndMap;
  return pipeline::parseWrapperConfig(yaml.c_str(), "defaults for " + robot + " / " + plugin);
}

}  // namespace comply::app
