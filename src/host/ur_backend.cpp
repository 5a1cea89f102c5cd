// `comply run --hardware ur` (ur_backend.hpp): the options, checked, into a UrArm and its clock.

#include "ur_backend.hpp"

#include <cmath>

#include "comply/ur/ur_arm.hpp"
#include "hardware_option.hpp"

namespace comply::host {
namespace {

constexpr const char* kOptions =
    "robot_ip=IPV4 (required), rtde_port, script_port, register_offset, watchdog_s, "
    "servoj_lookahead_s, servoj_gain, speedj_acceleration, link_timeout_s";

ur::UrArmOptions armOptions(const hardware::BackendContext& context) {
  ur::UrArmOptions options;
  for (const auto& [key, value] : context.options) {
    if (key == "robot_ip") {
      options.robot_ip = value;
    } else if (key == "rtde_port") {
      options.rtde_port = portOption(key, value);
    } else if (key == "script_port") {
      options.script_port = portOption(key, value);
    } else if (key == "register_offset") {
      options.program.register_offset = static_cast<int>(numberOption(key, value));
    } else if (key == "watchdog_s") {
      options.program.watchdog_s = numberOption(key, value);
    } else if (key == "servoj_lookahead_s") {
      options.program.servoj_lookahead_s = numberOption(key, value);
    } else if (key == "servoj_gain") {
      options.program.servoj_gain = numberOption(key, value);
    } else if (key == "speedj_acceleration") {
      options.program.speedj_acceleration_rad_per_s2 = numberOption(key, value);
    } else if (key == "link_timeout_s") {
      options.link_timeout_s = numberOption(key, value);
    } else {
      throw hardware::BackendError("the UR backend has no hardware option '" + key +
                                   "'; it takes " + kOptions);
    }
  }
  if (options.robot_ip.empty()) {
    throw hardware::BackendError(
        "the UR backend needs the controller's address: --hardware-option robot_ip=IPV4");
  }
  return options;
}

}  // namespace

HardwareBackend urArm(const pipeline::WrapperConfig& config,
                      const hardware::BackendContext& context) {
  ur::UrArmOptions options = armOptions(context);
  if (context.joints.size() != 6) {
    throw hardware::BackendError("a UR arm has 6 joints; the controller drives " +
                                 std::to_string(context.joints.size()));
  }
  // The controller's cycle paces the loop: comply's period must be it.
  if (std::abs(context.period_s - options.program.period_s) > 1e-9) {
    throw hardware::BackendError(
        "a UR e-series controller runs its cycle at 500 Hz: run the controller at --rate 500 "
        "(it is at " +
        std::to_string(1.0 / context.period_s) + " Hz)");
  }
  options.program.mode = config.output.mode;
  (void)ur::controlProgramScript(options.program);  // its checks, before connecting
  auto arm = std::make_shared<ur::UrArm>(options);
  HardwareBackend backend;
  backend.clock = std::make_unique<ur::UrClock>(*arm);
  const ur::ControllerVersion& version = arm->controllerVersion();
  backend.description = "a UR controller at " + options.robot_ip + " (PolyScope " +
                        std::to_string(version.major) + "." + std::to_string(version.minor) + "." +
                        std::to_string(version.bugfix) + ", " +
                        std::string(ur::driveCommand(options.program.mode)) + ")";
  backend.hardware = std::move(arm);
  return backend;
}

}  // namespace comply::host
