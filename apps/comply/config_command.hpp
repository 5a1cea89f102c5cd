#pragma once
// `comply config --defaults`: prints the documented controller file, every wrapper option at its
// default, for a robot and a plugin.

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace comply::app {

struct ConfigOptions {
  bool defaults = false;
  std::string robot = "fr3";
  std::string plugin = "cartesian_impedance";
  std::string name;  ///< controller name; default: the plugin's name
};

/// Adds the subcommand to `app`; `options` receives its values.
CLI::App* addConfigCommand(CLI::App& app, ConfigOptions& options);

/// Prints the file; exit code.
int configCommand(const ConfigOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
