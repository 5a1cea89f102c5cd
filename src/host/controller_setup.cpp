#include "comply/host/controller_setup.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "comply/core/text_file.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"

namespace comply::host {

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

}  // namespace comply::host

namespace comply::host {

pipeline::WrapperConfig simControllerConfig(const std::string& robot, const std::string& plugin,
                                            const std::string& config_file) {
  if (config_file.empty() || robot.empty()) {
    return controllerConfig(robot, plugin, config_file);
  }
  const TextFile text = readTextFile(config_file);
  if (!text.ok()) {
    throw std::runtime_error("controller config: " + text.error);
  }
  YAML::Node root;
  try {
    root = YAML::Load(text.text);
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(config_file + ": not valid YAML: " + error.what());
  }
  if (!root.IsMap() || root.size() != 1 || !root.begin()->second.IsMap() ||
      !root.begin()->second["ros__parameters"].IsMap()) {
    throw std::runtime_error(config_file +
                             ": expected one controller: '<name>: ros__parameters: ...'");
  }
  YAML::Node parameters = root.begin()->second["ros__parameters"];
  const bool other_robot = !parameters["robot"] || parameters["robot"].as<std::string>() != robot;
  if (other_robot) {
    for (const char* key : {"joints", "base_frame", "tip_frame"}) {
      if (parameters[key]) {
        throw std::runtime_error(config_file + " sets '" + key + "' for robot '" +
                                 parameters["robot"].as<std::string>("?") +
                                 "'; remove it to run the file on --robot " + robot);
      }
    }
    parameters["robot"] = robot;
  }
  if (!plugin.empty()) {
    parameters["plugin"] = plugin;
  }
  YAML::Emitter yaml;
  yaml << root;
  return pipeline::parseWrapperConfig(yaml.c_str(), config_file);
}

TcpPose homeTcpPose(const std::string& robot) {
  const model::RobotDescription description = model::loadRobotDescription(robot);
  const model::Model chain = description.loadModel();
  model::Data data(chain);
  const std::vector<double> zero(description.home.size(), 0.0);
  if (model::update(chain, data, description.home, zero, model::Quantity::kPose) !=
      model::UpdateStatus::kOk) {
    throw std::runtime_error("cannot compute the home pose of " + robot);
  }
  return {data.tip_position, data.tip_orientation};
}

}  // namespace comply::host
