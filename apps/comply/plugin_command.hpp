#pragma once
// `comply plugin new NAME --kind joint|cartesian --lang cpp|c [--out DIR]`: an out-of-tree plugin
// project built against the installed comply; `--kind hardware` (C++ only, no --lang) a hardware
// backend for `comply run --hardware` (include/comply/codegen/plugin.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct PluginNewOptions {
  std::string name;
  std::string kind;      ///< joint, cartesian or hardware
  std::string language;  ///< cpp or c; empty: not given (required for a law, cpp for hardware)
  std::string out;       ///< default ./NAME
};

int pluginNewCommand(const PluginNewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
