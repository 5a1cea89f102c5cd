#pragma once
// Hardware backends by name, for `comply run --hardware NAME`: built-in ones (`sim`, the MuJoCo
// plant in lock-step with the wall clock; `ur`, a UR e-series controller over RTDE) and backend
// libraries built out of tree (hardware/backend.hpp), found by path or as
// libcomply_hardware_<NAME>.so on the plugin search path.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "comply/hardware/backend.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/pipeline/config.hpp"

namespace comply::host {

/// A robot (or a plant) and the clock its loop runs on.
struct HardwareBackend {
  std::shared_ptr<hardware::HardwareInterface> hardware;
  std::unique_ptr<hardware::LoopClock> clock;
  std::string description;  ///< for the host's start-up line
};

/// `config` is completed for its robot (pipeline::completeForRobot: robot_description is set).
using HardwareFactory = std::function<HardwareBackend(const pipeline::WrapperConfig& config,
                                                      const hardware::BackendContext& context)>;

/// Adds a built-in backend under `name` (replacing one of that name).
void registerHardware(const std::string& name, HardwareFactory factory);
/// The registered names, sorted.
std::vector<std::string> hardwareNames();

/// What a backend is told about the controller `config` (completed for its robot) running at
/// `period_s`, with `options` (key=value).
hardware::BackendContext backendContext(const pipeline::WrapperConfig& config, double period_s,
                                        const std::vector<std::string>& options);

/// The backend `name`: a registered one, a path to a backend library, or a library
/// libcomply_hardware_<name>.so on the plugin search path. Throws hardware::BackendError naming
/// what was looked for and where.
HardwareBackend makeHardware(const std::string& name, const pipeline::WrapperConfig& config,
                             const hardware::BackendContext& context);

}  // namespace comply::host
