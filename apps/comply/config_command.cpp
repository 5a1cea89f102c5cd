#include "config_command.hpp"

#include <CLI/CLI.hpp>
#include <ostream>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::app {

CLI::App* addConfigCommand(CLI::App& app, ConfigOptions& options) {
  CLI::App* command = app.add_subcommand("config", "controller configuration files");
  command->add_flag("--defaults", options.defaults,
                    "print the documented file: every option at its default, with its unit");
  command->add_option("--robot", options.robot, "robot name or folder")->capture_default_str();
  command->add_option("--plugin", options.plugin, "plugin name or .so path")->capture_default_str();
  command->add_option("--name", options.name, "controller name (default: the plugin's)");
  return command;
}

int configCommand(const ConfigOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.defaults) {
    err << "comply config: say what to print (--defaults)\n";
    return 2;
  }
  const model::RobotDescription robot = model::loadRobotDescription(options.robot);
  const plugin::PluginLibrary library(options.plugin);
  const std::string name = options.name.empty() ? library.api().name : options.name;
  out << pipeline::documentedDefaults(name, options.plugin, options.robot, robot.tcp_frame,
                                      library.api().command_kind == COMPLY_COMMAND_CARTESIAN);
  return 0;
}

}  // namespace comply::app
