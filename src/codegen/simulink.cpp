#include "comply/codegen/simulink.hpp"

#include <sstream>

#include "comply/plugin/abi_layout.hpp"

namespace comply::codegen {
namespace {

using plugin::abi_layout::ScalarType;

// Simulink's name for each C type of abi.h. char (the message buffer) has no Simulink type of its
// own; int8 has its size and signedness on the targets comply runs on.
const char* simulinkType(ScalarType type) {
  switch (type) {
    case ScalarType::kDouble:
      return "double";
    case ScalarType::kInt32:
      return "int32";
    case ScalarType::kUint32:
      return "uint32";
    case ScalarType::kChar:
      return "int8";
  }
  return "double";
}

// A MATLAB character vector literal: quotes doubled.
std::string quoted(std::string_view text) {
  return "'" + replaceAll(std::string(text), "'", "''") + "'";
}

void writeBus(std::ostream& out, const plugin::abi_layout::Struct& bus) {
  out << "assignin('base', " << quoted(bus.name) << ", make_bus(" << quoted(bus.description)
      << ", { ...\n";
  for (const auto& element : bus.elements) {
    out << "  " << quoted(element.name) << ", " << element.count << ", "
        << quoted(simulinkType(element.type)) << ", " << quoted(element.description) << "; ...\n";
  }
  out << "}));\n";
}

}  // namespace

std::string simulinkBusesScript() {
  std::ostringstream out;
  out << "function comply_buses()\n"
         "%COMPLY_BUSES Simulink.Bus objects for comply's plugin ABI (comply/plugin/abi.h, ABI "
         "version "
      << COMPLY_ABI_VERSION
      << ").\n"
         "%   Written by `comply codegen simulink` from the structs of abi.h; regenerate rather "
         "than edit.\n"
         "%   Creates comply_input, comply_joint_command, comply_cartesian_command and "
         "comply_output in\n"
         "%   the base workspace. Every bus is Imported from abi.h, so Embedded Coder's code uses "
         "comply's\n"
         "%   structs as they are (add comply's include folder to the model's include path). "
         "Arrays have\n"
         "%   fixed capacities (COMPLY_MAX_DOF = "
      << COMPLY_MAX_DOF
      << "); the first `dof` entries are valid. Matrices are\n"
         "%   flattened exactly as in C: see each element's description for the layout.\n";
  for (const auto& bus : plugin::abi_layout::kStructs) {
    writeBus(out, bus);
  }
  out << "end\n\n"
         "function bus = make_bus(description, rows)\n"
         "bus = Simulink.Bus;\n"
         "bus.Description = description;\n"
         "bus.DataScope = 'Imported';\n"
         "bus.HeaderFile = 'comply/plugin/abi.h';\n"
         "for k = 1:size(rows, 1)\n"
         "  element = Simulink.BusElement;\n"
         "  element.Name = rows{k, 1};\n"
         "  element.Dimensions = rows{k, 2};\n"
         "  element.DataType = rows{k, 3};\n"
         "  element.Description = rows{k, 4};\n"
         "  element.Complexity = 'real';\n"
         "  if k == 1\n"
         "    elements = element;\n"
         "  else\n"
         "    elements(k) = element;\n"
         "  end\n"
         "end\n"
         "bus.Elements = elements;\n"
         "end\n";
  return out.str();
}

std::vector<GeneratedFile> simulinkFiles() {
  std::vector<GeneratedFile> files;
  files.push_back({"comply_buses.m", simulinkBusesScript()});
  files.push_back({"comply_new_model.m",
                   replaceAll(std::string(embeddedTemplate("simulink/comply_new_model.m")),
                              "COMPLY_MAX_DOF_VALUE", std::to_string(COMPLY_MAX_DOF))});
  files.push_back({"comply_simulink_adapter.c",
                   std::string(embeddedTemplate("simulink/comply_simulink_adapter.c"))});
  files.push_back({"CMakeLists.txt", std::string(embeddedTemplate("simulink/CMakeLists.txt"))});
  return files;
}

}  // namespace comply::codegen
