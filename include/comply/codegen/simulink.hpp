#pragma once
// `comply codegen simulink`: what a Simulink user needs to draw a comply control law and turn
// Embedded Coder's output into a plugin. The buses come from abi_layout.hpp, so they follow abi.h.

#include <vector>

#include "comply/codegen/generated_file.hpp"

namespace comply::codegen {

/// comply_buses.m: Simulink.Bus objects comply_input, comply_joint_command,
/// comply_cartesian_command and comply_output, imported from comply/plugin/abi.h.
std::string simulinkBusesScript();

/// comply_buses.m, comply_new_model.m, comply_simulink_adapter.c and CMakeLists.txt.
std::vector<GeneratedFile> simulinkFiles();

}  // namespace comply::codegen
