#include "codegen_command.hpp"

#include <ostream>

#include "comply/codegen/simulink.hpp"

namespace comply::app {

int codegenSimulinkCommand(const CodegenOptions& options, std::ostream& out, std::ostream& err) {
  (void)err;
  const auto files = codegen::simulinkFiles();
  codegen::writeFiles(options.out, files);
  for (const auto& file : files) {
    out << (std::filesystem::path(options.out) / file.path).string() << "\n";
  }
  return 0;
}

}  // namespace comply::app
