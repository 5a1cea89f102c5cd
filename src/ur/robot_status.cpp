// A UR controller's modes by name, and why an arm does not take commands (robot_status.hpp).

#include "comply/ur/robot_status.hpp"

#include <array>

namespace comply::ur {

std::string_view robotModeName(std::int32_t mode) noexcept {
  static constexpr std::array<std::string_view, 10> kNames{
      "NO_CONTROLLER", "DISCONNECTED", "CONFIRM_SAFETY", "BOOTING", "POWER_OFF",
      "POWER_ON",      "IDLE",         "BACKDRIVE",      "RUNNING", "UPDATING_FIRMWARE"};
  const std::int32_t index = mode + 1;
  return index >= 0 && index < static_cast<std::int32_t>(kNames.size())
             ? kNames[static_cast<std::size_t>(index)]
             : "UNKNOWN";
}

std::string_view safetyModeName(std::int32_t mode) noexcept {
  static constexpr std::array<std::string_view, 14> kNames{"?",
                                                           "NORMAL",
                                                           "REDUCED",
                                                           "PROTECTIVE_STOP",
                                                           "RECOVERY",
                                                           "SAFEGUARD_STOP",
                                                           "SYSTEM_EMERGENCY_STOP",
                                                           "ROBOT_EMERGENCY_STOP",
                                                           "VIOLATION",
                                                           "FAULT",
                                                           "VALIDATE_JOINT_ID",
                                                           "UNDEFINED_SAFETY_MODE",
                                                           "AUTOMATIC_MODE_SAFEGUARD_STOP",
                                                           "SYSTEM_THREE_POSITION_ENABLING_STOP"};
  return mode >= 1 && mode < static_cast<std::int32_t>(kNames.size())
             ? kNames[static_cast<std::size_t>(mode)]
             : "UNKNOWN";
}

std::string_view runtimeStateName(std::uint32_t state) noexcept {
  static constexpr std::array<std::string_view, 6> kNames{"STOPPING", "STOPPED", "PLAYING",
                                                          "PAUSING",  "PAUSED",  "RESUMING"};
  return state < kNames.size() ? kNames[state] : "UNKNOWN";
}

const char* stopReason(std::int32_t robot_mode, std::int32_t safety_mode,
                       std::uint32_t runtime_state, bool program_running) noexcept {
  switch (static_cast<SafetyMode>(safety_mode)) {
    case SafetyMode::kNormal:
    case SafetyMode::kReduced:
      break;
    case SafetyMode::kProtectiveStop:
      return "protective stop (safety mode PROTECTIVE_STOP): clear it on the teach pendant or "
             "with the dashboard's 'unlock protective stop', then reset";
    case SafetyMode::kSystemEmergencyStop:
    case SafetyMode::kRobotEmergencyStop:
      return "emergency stop (safety mode EMERGENCY_STOP): release the button, then reset";
    case SafetyMode::kSafeguardStop:
    case SafetyMode::kAutomaticModeSafeguardStop:
      return "safeguard stop (safety mode SAFEGUARD_STOP): a safety input is open";
    case SafetyMode::kThreePositionEnablingStop:
      return "three-position enabling stop: the enabling device was released";
    case SafetyMode::kViolation:
    case SafetyMode::kFault:
      return "safety fault or violation: the controller must be restarted";
    default:
      return "the controller is not in NORMAL safety mode";
  }
  if (robot_mode != static_cast<std::int32_t>(RobotMode::kRunning)) {
    return "the arm is not powered on with its brakes released (robot mode is not RUNNING)";
  }
  if (runtime_state != static_cast<std::uint32_t>(RuntimeState::kPlaying) || !program_running) {
    return "comply's control program is not running on the controller (stopped on the robot, "
           "or by its watchdog)";
  }
  return nullptr;
}

}  // namespace comply::ur
