#pragma once
// `comply plugin new NAME --kind joint|cartesian --lang cpp|c [--out DIR]`: an out-of-tree plugin
// project built against the installed comply (include/comply/codegen/plugin.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct PluginNewOptions {
  std::string name;
  std::string kind;
  std::string language;
  std::string out;  ///< default ./NAME
};

int pluginNewCommand(const PluginNewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
