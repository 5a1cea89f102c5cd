#pragma once
// A UR controller's robot mode, safety mode and program state as RTDE reports them
// (robot_mode, safety_mode, runtime_state), with their names, and what comply's UR backend makes
// of them: whether the arm takes commands, and if not, why (HardwareInterface::robotStop).

#include <cstdint>
#include <string_view>

namespace comply::ur {

enum class RobotMode : std::int32_t {
  kNoController = -1,
  kDisconnected = 0,
  kConfirmSafety = 1,
  kBooting = 2,
  kPowerOff = 3,
  kPowerOn = 4,
  kIdle = 5,
  kBackdrive = 6,
  kRunning = 7,
  kUpdatingFirmware = 8,
};

enum class SafetyMode : std::int32_t {
  kNormal = 1,
  kReduced = 2,
  kProtectiveStop = 3,
  kRecovery = 4,
  kSafeguardStop = 5,
  kSystemEmergencyStop = 6,
  kRobotEmergencyStop = 7,
  kViolation = 8,
  kFault = 9,
  kValidateJointId = 10,
  kUndefined = 11,
  kAutomaticModeSafeguardStop = 12,
  kThreePositionEnablingStop = 13,
};

enum class RuntimeState : std::uint32_t {
  kStopping = 0,
  kStopped = 1,
  kPlaying = 2,
  kPausing = 3,
  kPaused = 4,
  kResuming = 5,
};

std::string_view robotModeName(std::int32_t mode) noexcept;
std::string_view safetyModeName(std::int32_t mode) noexcept;
std::string_view runtimeStateName(std::uint32_t state) noexcept;

/// What the controller's state says about an arm comply drives: nullptr when it takes commands
/// (powered and running, in NORMAL or REDUCED safety, comply's program playing), else why not,
/// as a text with static storage (JointState::robot_stop). `program_running`: the program's own
/// flag (control_program.hpp, 1 while it runs).
const char* stopReason(std::int32_t robot_mode, std::int32_t safety_mode,
                       std::uint32_t runtime_state, bool program_running) noexcept;

}  // namespace comply::ur
