#include "codegen_command.hpp"

#include <ostream>

#include "comply/codegen/simulink.hpp"
#include "comply/core/output_folder.hpp"

namespace comply::app {

int codegenSimulinkCommand(const CodegenOptions& options, std::ostream& out, std::ostream& err) {
  (void)err;
  const auto files = codegen::simulinkFiles();
  makeOutputFolder(options.out);  // its parent must exist; the files' own subfolders are made
  codegen::writeFiles(options.out, files);
  for (const auto& file : files) {
    out << (std::filesystem::path(options.out) / file.path).string() << "\n";
  }
  return 0;
}

}  // namespace comply::app
