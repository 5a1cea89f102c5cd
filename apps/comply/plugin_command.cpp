#include "plugin_command.hpp"

#include <filesystem>
#include <ostream>
#include <string>

#include "comply/codegen/plugin.hpp"
#include "comply/core/output_folder.hpp"

namespace comply::app {
namespace {

/// The language the project is written in, or empty after saying on `err` why none fits.
std::string projectLanguage(const PluginNewOptions& options, std::ostream& err) {
  if (options.kind == "hardware") {
    // HardwareInterface is a C++ class: there is no C backend to offer.
    if (!options.language.empty() && options.language != "cpp") {
      err << "comply plugin new: --lang " << options.language
          << " does not apply to --kind hardware: a backend implements the C++ class "
             "HardwareInterface; leave --lang out\n";
      return {};
    }
    return "cpp";
  }
  if (options.language.empty()) {
    err << "comply plugin new: --lang cpp|c is required for a " << options.kind << " law\n";
  }
  return options.language;
}

}  // namespace

int pluginNewCommand(const PluginNewOptions& options, std::ostream& out, std::ostream& err) {
  if (const auto problem = codegen::pluginNameProblem(options.name); !problem.empty()) {
    err << "comply plugin new: " << problem << "\n";
    return 2;
  }
  const std::string language = projectLanguage(options, err);
  if (language.empty()) {
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
  const auto files =
      codegen::pluginFiles({.name = options.name, .kind = options.kind, .language = language});
  makeOutputFolder(folder);  // its parent must exist; the project's own subfolders are made
  codegen::writeFiles(folder, files);
  for (const auto& file : files) {
    out << (folder / file.path).string() << "\n";
  }
  return 0;
}

}  // namespace comply::app
