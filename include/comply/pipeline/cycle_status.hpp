#pragma once

namespace comply::pipeline {

/// What one cycle of the law did (Controller::update).
enum class CycleStatus {
  kOk,
  kInactive,  ///< not activated: torque output untouched
  kFault,     ///< in FAULT: the controlled stop's torque was written
};

}  // namespace comply::pipeline
