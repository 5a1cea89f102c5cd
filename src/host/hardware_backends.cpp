// Hardware backends by name (see hardware_backends.hpp).

#include "comply/host/hardware_backends.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "comply/core/named_registry.hpp"
#include "comply/plugin/loader.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "franka_backend.hpp"
#include "ur_backend.hpp"

namespace comply::host {
namespace {

/// `fx,fy,fz,tx,ty,tz` as a wrench.
Vector6d wrenchOption(const std::string& key, const std::string& text) {
  Vector6d wrench;
  std::istringstream in(text);
  for (int i = 0; i < 6; ++i) {
    char comma = ',';
    if (!(in >> wrench[i]) || !std::isfinite(wrench[i]) || (i < 5 && !(in >> comma)) ||
        comma != ',') {
      throw hardware::BackendError("--hardware-option " + key + "='" + text +
                                   "': expected six numbers fx,fy,fz,tx,ty,tz [N, N m]");
    }
  }
  if (in >> std::ws; !in.eof()) {
    throw hardware::BackendError("--hardware-option " + key + "='" + text +
                                 "': more than six numbers");
  }
  return wrench;
}

/// The MuJoCo plant, paced to the wall clock: what `comply run --sim` drives. Takes
/// `--hardware-option wrench_offset=fx,fy,fz,tx,ty,tz`: its wrist sensor's offset in the sensor
/// (TCP) frame, what a tare removes; and `torque_sensing=link`: the effort reads as joint-torque
/// sensors on the link side of the joints' friction (`drive`, the default: the drive's torque).
HardwareBackend simulatedArm(const pipeline::WrapperConfig& config,
                             const hardware::BackendContext& context) {
  sim::PlantOptions options;
  for (const auto& [key, value] : context.options) {
    if (key == "torque_sensing" && (value == "link" || value == "drive")) {
      options.link_side_torque = value == "link";
    } else if (key == "wrench_offset") {
      options.wrench_sensor_offset = wrenchOption(key, value);
    } else {
      throw hardware::BackendError(
          "the simulated arm has no hardware option '" + key + "=" + value +
          "'; it takes wrench_offset=fx,fy,fz,tx,ty,tz [N, N m] and torque_sensing=link|drive");
    }
  }
  options.control_period_s = context.period_s;
  options.tip_frame = config.tip_frame;
  options.actuation = config.output.mode;  // the arm has the drives the controller drives
  auto plant = std::make_shared<sim::SimulatedRobot>(*config.robot_description, options);
  HardwareBackend backend;
  backend.clock = std::make_unique<sim::SimulatedClock>(*plant, true);
  backend.description = "a simulated " + config.robot_description->name + " (MuJoCo, " +
                        std::string(toString(config.output.mode)) + " drives)";
  backend.hardware = std::move(plant);
  return backend;
}

NamedRegistry<HardwareFactory>& registry() {
  static NamedRegistry<HardwareFactory> instance(
      {{"sim", simulatedArm}, {"ur", urArm}, {"franka", frankaArm}});
  return instance;
}

HardwareBackend fromLibrary(const std::filesystem::path& library,
                            const hardware::BackendContext& context) {
  auto handle =
      std::make_shared<hardware::BackendHandle>(hardware::loadBackendLibrary(library, context));
  HardwareBackend backend;
  // Aliasing: the interface lives as long as the handle that unloads its library after it.
  backend.hardware = std::shared_ptr<hardware::HardwareInterface>(handle, handle->get());
  backend.clock = std::make_unique<hardware::WallClock>();
  backend.description = library.string();
  return backend;
}

}  // namespace

void registerHardware(const std::string& name, HardwareFactory factory) {
  registry().add(name, std::move(factory));
}

std::vector<std::string> hardwareNames() {
  return registry().names();
}

hardware::BackendContext backendContext(const pipeline::WrapperConfig& config, double period_s,
                                        const std::vector<std::string>& options) {
  const model::RobotDescription& robot = *config.robot_description;
  hardware::BackendContext context;
  context.robot_name = robot.name;
  context.robot_folder = robot.folder;
  context.urdf_path = robot.urdf_path;
  context.joints = config.joints;
  context.tip_frame = config.tip_frame;
  context.period_s = period_s;
  // robot.yaml's home is in its own joint order; the backend gets the controller's.
  for (const std::string& joint : context.joints) {
    const auto found = std::find(robot.joints.begin(), robot.joints.end(), joint);
    const auto index = static_cast<std::size_t>(found - robot.joints.begin());
    context.home_position.push_back(index < robot.home.size() ? robot.home[index] : 0.0);
  }
  for (const std::string& option : options) {
    const std::size_t equals = option.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw hardware::BackendError("--hardware-option '" + option + "' is not key=value");
    }
    context.options[option.substr(0, equals)] = option.substr(equals + 1);
  }
  return context;
}

HardwareBackend makeHardware(const std::string& name, const pipeline::WrapperConfig& config,
                             const hardware::BackendContext& context) {
  if (const HardwareFactory factory = registry().find(name)) {
    return factory(config, context);
  }
  // A library is found as control-law plugins are: a path, or libcomply_<name>.so on the plugin
  // search path, here with the name hardware_<name>.
  const bool path = name.find('/') != std::string::npos || name.ends_with(".so");
  std::filesystem::path library;
  try {
    library = plugin::resolvePlugin(path ? name : "hardware_" + name);
  } catch (const plugin::PluginError& error) {
    throw hardware::BackendError("no hardware backend '" + name + "': not built in (" +
                                 registry().list() + "), and " + error.what());
  }
  return fromLibrary(library, context);
}

}  // namespace comply::host
