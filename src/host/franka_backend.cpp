// `comply run --hardware franka` (franka_backend.hpp): the options, checked, into a FrankaArm and
// its clock.

#include "franka_backend.hpp"

#include <cmath>

#include "comply/franka/fci_session.hpp"
#include "comply/franka/franka_arm.hpp"
#include "hardware_option.hpp"

namespace comply::host {
namespace {

constexpr const char* kOptions =
    "robot_ip=IPV4 (required), client=libfranka|comply, command_port (comply's client), "
    "realtime=enforce|ignore (libfranka's), collision_torque_n_m, collision_force_n, "
    "link_timeout_s";

struct FrankaOptions {
  franka::FciSessionOptions session;
  std::string client = "libfranka";
  bool realtime = true;
  double collision_torque_n_m = 20.0;  // libfranka's examples' defaults
  double collision_force_n = 20.0;
  double link_timeout_s = 0.1;
};

FrankaOptions frankaOptions(const hardware::BackendContext& context) {
  FrankaOptions options;
  if (!libfrankaBuiltIn()) {
    options.client = "comply";  // this build has no libfranka
  }
  for (const auto& [key, value] : context.options) {
    if (key == "robot_ip") {
      options.session.robot_ip = value;
    } else if (key == "client" && (value == "libfranka" || value == "comply")) {
      options.client = value;
    } else if (key == "command_port") {
      options.session.command_port = portOption(key, value);
    } else if (key == "realtime" && (value == "enforce" || value == "ignore")) {
      options.realtime = value == "enforce";
    } else if (key == "collision_torque_n_m") {
      options.collision_torque_n_m = numberOption(key, value);
    } else if (key == "collision_force_n") {
      options.collision_force_n = numberOption(key, value);
    } else if (key == "link_timeout_s") {
      options.link_timeout_s = numberOption(key, value);
    } else {
      throw hardware::BackendError("the Franka backend has no hardware option '" + key + "=" +
                                   value + "'; it takes " + kOptions);
    }
  }
  if (options.session.robot_ip.empty()) {
    throw hardware::BackendError(
        "the Franka backend needs the robot's address: --hardware-option robot_ip=IPV4 (the "
        "robot's FCI address, not its Desk's)");
  }
  return options;
}

}  // namespace

HardwareBackend frankaArm(const pipeline::WrapperConfig& config,
                          const hardware::BackendContext& context) {
  const FrankaOptions options = frankaOptions(context);
  if (context.joints.size() != 7) {
    throw hardware::BackendError("a Franka arm has 7 joints; the controller drives " +
                                 std::to_string(context.joints.size()));
  }
  if (std::abs(context.period_s - 0.001) > 1e-9) {
    throw hardware::BackendError(
        "a Franka robot sends its state every millisecond and wants a torque for each: run the "
        "controller at --rate 1000 (it is at " +
        std::to_string(1.0 / context.period_s) + " Hz)");
  }
  if (config.output.mode != OutputMode::kTorque) {
    throw hardware::BackendError(
        std::string("the Franka backend drives the robot's torque control: output.mode must be "
                    "torque (it is ") +
        std::string(toString(config.output.mode)) + ")");
  }
  franka::FrankaArmOptions arm_options;
  arm_options.collision =
      franka::frankaCollisionThresholds(options.collision_torque_n_m, options.collision_force_n);
  arm_options.link_timeout_s = options.link_timeout_s;
  std::unique_ptr<franka::FrankaSession> session;
  if (options.client == "libfranka") {
    session = makeLibfrankaSession(options.session.robot_ip, options.realtime);
    if (!session) {
      throw hardware::BackendError(
          "this comply was built without libfranka: use --hardware-option client=comply (the "
          "robot's system 5.5, FCI protocol 7), or build comply with libfranka (docs/franka.md)");
    }
  } else {
    session = franka::makeFciSession(options.session);
  }
  auto arm = std::make_shared<franka::FrankaArm>(std::move(session), arm_options);
  HardwareBackend backend;
  backend.clock = std::make_unique<franka::FrankaClock>(*arm);
  backend.description = "a Franka robot at " + options.session.robot_ip + " (" +
                        arm->session().description() + ", torque control)";
  backend.hardware = std::move(arm);
  return backend;
}

}  // namespace comply::host
