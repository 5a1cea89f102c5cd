#pragma once
// `comply codegen simulink --out DIR`: the Simulink buses, a template model and the adapter that
// turns Embedded Coder's output into a plugin (include/comply/codegen/simulink.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct CodegenOptions {
  std::string out = "comply_simulink";
};

int codegenSimulinkCommand(const CodegenOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
