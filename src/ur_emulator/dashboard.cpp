// The emulated controller's dashboard server: one answer per command line, in the words of a
// PolyScope 5 dashboard (ur_emulator.hpp lists the commands it knows).

#include <string>

#include "comply/ur/robot_status.hpp"
#include "emulator_impl.hpp"

namespace comply::ur {
namespace {

std::string versionText(const ControllerVersion& v) {
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.bugfix) +
         "." + std::to_string(v.build);
}

}  // namespace

std::string UrEmulator::Impl::dashboard(const std::string& command) {
  const std::lock_guard lock(mutex_);
  if (command == "unlock protective stop") {
    if (safety_mode_ != 3) {
      return "Cannot unlock protective stop: the robot is not protectively stopped";
    }
    const double since_s = static_cast<double>(cycle_) * options_.period_s - stopped_at_s_;
    if (since_s < options_.unlock_delay_s) {
      return "Cannot unlock protective stop until " + std::to_string(options_.unlock_delay_s) +
             "s after occurrence. Always inspect cause of protective stop before unlocking";
    }
    safety_mode_ = 1;
    return "Protective stop releasing";
  }
  if (command == "safetymode" || command == "safetystatus") {
    return std::string(command == "safetymode" ? "Safetymode: " : "Safetystatus: ") +
           std::string(safetyModeName(safety_mode_));
  }
  if (command == "robotmode") {
    return "Robotmode: RUNNING";
  }
  if (command == "programState") {
    return std::string(running_ ? "PLAYING" : "STOPPED") + " comply_control";
  }
  if (command == "running") {
    return std::string("Program running: ") + (running_ ? "true" : "false");
  }
  if (command == "stop") {
    if (!running_) {
      return "Failed to execute: stop";
    }
    stopProgram(program_flag_);
    return "Stopped";
  }
  if (command == "close safety popup") {
    return "closing safety popup";
  }
  if (command == "PolyscopeVersion") {
    return "URSoftware " + versionText(options_.version) + " (comply's emulator)";
  }
  if (command == "quit") {
    return "Disconnected";
  }
  return "could not understand: '" + command + "'";
}

}  // namespace comply::ur
