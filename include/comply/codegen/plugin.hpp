#pragma once
// `comply plugin new`: an out-of-tree plugin project (CMakeLists.txt, the law, a test that loads
// the built library, validate samples, a controller YAML and a task for comply sim), from the
// templates under src/codegen/templates/plugin; or, of kind hardware, a hardware backend
// (CMakeLists.txt, a HardwareInterface simulating an arm, a README) from templates/hardware.

#include <string>
#include <string_view>
#include <vector>

#include "comply/codegen/generated_file.hpp"

namespace comply::codegen {

struct PluginSpec {
  std::string
      name;  ///< a C identifier: libcomply_<name>.so, a backend libcomply_hardware_<name>.so
  std::string kind = "joint";    ///< joint or cartesian (a law), or hardware (a backend)
  std::string language = "cpp";  ///< cpp (the SDK) or c (abi.h alone); a backend is cpp
};

/// Empty when `name` can name a plugin, else why not. The name becomes C and CMake identifiers
/// and a file name, so it must be a C identifier.
std::string pluginNameProblem(std::string_view name);

/// The project's files; throws std::invalid_argument for a bad name, kind or language.
std::vector<GeneratedFile> pluginFiles(const PluginSpec& spec);

}  // namespace comply::codegen
