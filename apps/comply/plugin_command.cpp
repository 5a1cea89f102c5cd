#include "plugin_command.hpp"

#include <filesystem>
#include <ostream>

#include "comply/codegen/plugin.hpp"

namespace comply::app {

int pluginNewCommand(const PluginNewOptions& options, std::ostream& out, std::ostream& err) {
  if (const auto problem = codegen::pluginNameProblem(options.name); !problem.empty()) {
    err << "comply plugin new: " << problem << "\n";
    return 2;
  }
  const std::filesystem::path folder = options.out.empty() ? options.name : options.out;
  // Never mix the project into someone's files or overwrite an earlier project's edited law.
  std::error_code error;
  if (std::filesystem::exists(folder, error) && (!std::filesystem::is_directory(folder, error) ||
                                                 !std::filesystem::is_empty(folder, error))) {
    err << "comply plugin new: " << folder.string()
        << " exists and is not an empty folder; choose another --out\n";
    return 2;
  }
  const auto files = codegen::pluginFiles(
      {.name = options.name, .kind = options.kind, .language = options.language});
  codegen::writeFiles(folder, files);
  for (const auto& file : files) {
    out << (folder / file.path).string() << "\n";
  }
  return 0;
}

}  // namespace comply::app
