// Hardware backends by name (see hardware_backends.hpp).

#include "comply/host/hardware_backends.hpp"

#include "comply/core/named_registry.hpp"
#include "comply/plugin/loader.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::host {
namespace {

/// The MuJoCo plant, paced to the wall clock: what `comply run --sim` drives.
HardwareBackend simulatedArm(const pipeline::ResolvedController& resolved,
                             const hardware::BackendContext& context) {
  sim::PlantOptions options;
  options.control_period_s = context.period_s;
  options.tip_frame = resolved.config.tip_frame;
  auto plant = std::make_shared<sim::SimulatedRobot>(resolved.robot, options);
  HardwareBackend backend;
  backend.clock = std::make_unique<sim::SimulatedClock>(*plant, true);
  backend.description = "a simulated " + resolved.robot.name + " (MuJoCo)";
  backend.hardware = std::move(plant);
  return backend;
}

NamedRegistry<HardwareFactory>& registry() {
  static NamedRegistry<HardwareFactory> instance({{"sim", simulatedArm}});
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

hardware::BackendContext backendContext(const pipeline::ResolvedController& resolved,
                                        double period_s, const std::vector<std::string>& options) {
  hardware::BackendContext context;
  context.robot_name = resolved.robot.name;
  context.robot_folder = resolved.robot.folder;
  context.urdf_path = resolved.robot.urdf_path;
  context.joints = resolved.config.joints;
  context.tip_frame = resolved.config.tip_frame;
  context.period_s = period_s;
  // robot.yaml's home is in its own joint order; the backend gets the controller's.
  for (const std::string& joint : context.joints) {
    double home = 0.0;
    for (std::size_t i = 0; i < resolved.robot.joints.size() && i < resolved.robot.home.size();
         ++i) {
      if (resolved.robot.joints[i] == joint) {
        home = resolved.robot.home[i];
      }
    }
    context.home_position.push_back(home);
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

HardwareBackend makeHardware(const std::string& name, const pipeline::ResolvedController& resolved,
                             const hardware::BackendContext& context) {
  const HardwareFactory factory = registry().find(name);
  if (factory) {
    return factory(resolved, context);
  }
  if (name.find('/') != std::string::npos || std::filesystem::path(name).extension() == ".so") {
    return fromLibrary(name, context);
  }
  const std::string file = "libcomply_hardware_" + name + ".so";
  std::string searched;
  for (const std::filesystem::path& folder : plugin::pluginSearchPath()) {
    if (std::filesystem::exists(folder / file)) {
      return fromLibrary(folder / file, context);
    }
    searched += (searched.empty() ? "" : ", ") + folder.string();
  }
  throw hardware::BackendError("no hardware backend '" + name + "': not built in (" +
                               registry().list() + "), not a path to a library, and no " + file +
                               " in " + (searched.empty() ? "the plugin search path" : searched));
}

}  // namespace comply::host
