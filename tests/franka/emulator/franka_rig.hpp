#pragma once
// comply's Cartesian impedance on the emulated FR3 through the host's `franka` backend (comply's
// own FCI client), as `comply run --hardware franka` runs it: the control loop on the robot's
// states, on a thread of its own.

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "../../support/eventually.hpp"
#include "comply/franka/franka_arm.hpp"
#include "comply/franka_emulator/franka_emulator.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/hardware_backends.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::franka::test {

inline const std::filesystem::path kSourceDir = COMPLY_SOURCE_DIR;

inline FrankaEmulatorOptions waitingEmulator() {
  FrankaEmulatorOptions options;
  options.command_port = 0;
  options.answer_wait_s = 0.5;  // a busy host's scheduling does not lose cycles
  return options;
}

using comply::testing::eventually;

/// config/sim/cartesian_impedance.yaml on the FR3.
inline pipeline::WrapperConfig frankaConfig() {
  return host::simControllerConfig(
      "fr3", "", (kSourceDir / "config" / "sim" / "cartesian_impedance.yaml").string());
}

struct FrankaRig {
  FrankaRig(const FrankaEmulator& emulator, const std::vector<std::string>& extra_options = {},
            pipeline::WrapperConfig controller = frankaConfig())
      : config(withRobotsGravity(std::move(controller))),
        backend(makeBackend(emulator, config, extra_options)),
        wrapper(config),
        loop(*backend.hardware, wrapper, *backend.clock, {.period_s = 0.001}) {
    JointState state = JointState::zero(7);
    (void)backend.hardware->read(state);
    wrapper.activate(state);
    thread = std::jthread([this] { (void)loop.run(); });
  }
  ~FrankaRig() {
    loop.stop();
    thread = {};
  }
  FrankaRig(const FrankaRig&) = delete;
  FrankaRig& operator=(const FrankaRig&) = delete;

  [[nodiscard]] FrankaArm& arm() { return static_cast<FrankaArm&>(*backend.hardware); }
  [[nodiscard]] pipeline::WrapperState state() const { return wrapper.diagnostics().state; }
  bool faultsWith(const std::string& text, double timeout_s = 3.0) const {
    return eventually(
        [&] {
          const auto diagnostics = wrapper.diagnostics();
          return diagnostics.state == pipeline::WrapperState::kFault &&
                 diagnostics.last_fault.find(text) != std::string::npos;
        },
        timeout_s);
  }

  /// As the live host: the robot compensates gravity itself, comply adds none.
  static pipeline::WrapperConfig withRobotsGravity(pipeline::WrapperConfig config) {
    config.hardware_compensates_gravity = true;
    return config;
  }

  static host::HardwareBackend makeBackend(const FrankaEmulator& emulator,
                                           const pipeline::WrapperConfig& config,
                                           const std::vector<std::string>& extra_options) {
    // The emulator waits up to 0.5 s for each command before its next state (answer_wait_s): a
    // host's stall of the control thread is not a lost link.
    std::vector<std::string> options{"robot_ip=127.0.0.1", "client=comply",
                                     "command_port=" + std::to_string(emulator.commandPort()),
                                     "link_timeout_s=0.6"};
    options.insert(options.end(), extra_options.begin(), extra_options.end());
    return host::makeHardware("franka", config, host::backendContext(config, 0.001, options));
  }

  pipeline::WrapperConfig config;
  host::HardwareBackend backend;
  pipeline::CartesianWrapper wrapper;
  hardware::ControlLoop loop;
  std::jthread thread;
};

}  // namespace comply::franka::test
