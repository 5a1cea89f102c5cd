#pragma once
// Conversion between the C++ command types (core) and the plugin buses (abi.h).

#include "comply/core/commands.hpp"
#include "comply/plugin/abi.h"

namespace comply::pipeline {

comply_cartesian_command toBus(const CartesianCommand& command, int dof);
comply_joint_command toBus(const JointCommand& command, int dof);

}  // namespace comply::pipeline
