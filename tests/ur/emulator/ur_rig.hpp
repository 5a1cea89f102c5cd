#pragma once
// comply's Cartesian impedance on the emulated UR5e through the host's `ur` backend, as
// `comply run --hardware ur` runs it: the controller file, the backend's options, its clock on
// the controller's cycles, the control loop on a thread of its own.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/hardware_backends.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/ur/ur_arm.hpp"
#include "ur_emulator_support.hpp"

namespace comply::ur::test {

inline const std::filesystem::path kSourceDir = COMPLY_SOURCE_DIR;
inline constexpr double kUrPeriodS = 0.002;

/// config/sim/cartesian_impedance.yaml on the UR5e with `mode`.
inline pipeline::WrapperConfig urConfig(OutputMode mode) {
  pipeline::WrapperConfig config = host::simControllerConfig(
      "ur5e", "", (kSourceDir / "config" / "sim" / "cartesian_impedance.yaml").string());
  config.output.mode = mode;
  return config;
}

/// The emulated UR5e with the probe, over a table whose top is 1 cm below the probe's tip at
/// home; returns the options and the tip's height at home.
inline UrEmulatorOptions probeOverTable(double& tip_z) {
  UrEmulatorOptions options = freePorts();
  options.scene.tool = kSourceDir / "examples" / "sim" / "probe_tool.xml";
  sim::PlantOptions plant;
  plant.scene.tool = options.scene.tool;
  const sim::SimulatedRobot probe(model::loadRobotDescription("ur5e"), plant);
  const Eigen::Isometry3d tcp = probe.tcpPose();
  const Eigen::Vector3d tip = tcp * Eigen::Vector3d(0.0, 0.0, 0.11);  // the ball's lowest point
  tip_z = tip.z();
  const double top = tip.z() - 0.01;
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("comply_ur_table_" + std::to_string(::getpid()) + ".xml");
  std::ofstream(file) << "<mujocoinclude>\n  <body name=\"table\" pos=\"" << tip.x() << " "
                      << tip.y() << " " << top / 2.0
                      << "\">\n    <geom name=\"table_top\" type=\"box\" size=\"0.1 0.1 "
                      << top / 2.0
                      << "\" friction=\"0.3 0.005 0.0001\" solref=\"0.005 1\"/>\n  </body>\n"
                         "</mujocoinclude>\n";
  options.scene.objects = {file};
  return options;
}

/// The controller on the emulated arm, its loop running until the rig goes.
struct UrRig {
  UrRig(UrEmulator& emulator, pipeline::WrapperConfig config,
        const std::vector<std::string>& extra_options = {})
      : backend(makeBackend(emulator, config, extra_options)),
        wrapper(withRobotsGravity(std::move(config), *backend.hardware)),
        loop(*backend.hardware, wrapper, *backend.clock, {.period_s = kUrPeriodS}) {
    JointState state = JointState::zero(6);
    (void)backend.hardware->read(state);
    state.wrench_valid = backend.hardware->readWrench(state.wrench);
    wrapper.activate(state);
    thread = std::jthread([this] { (void)loop.run(); });
  }
  ~UrRig() {
    loop.stop();
    thread = {};
  }
  UrRig(const UrRig&) = delete;
  UrRig& operator=(const UrRig&) = delete;

  [[nodiscard]] UrArm& arm() { return static_cast<UrArm&>(*backend.hardware); }

  /// As the live host: a robot that compensates gravity itself gets none from comply.
  static pipeline::WrapperConfig withRobotsGravity(pipeline::WrapperConfig config,
                                                   const hardware::HardwareInterface& robot) {
    config.hardware_compensates_gravity = robot.compensatesGravity();
    return config;
  }

  static host::HardwareBackend makeBackend(const UrEmulator& emulator,
                                           const pipeline::WrapperConfig& config,
                                           const std::vector<std::string>& extra_options) {
    // The tests' emulator waits up to 0.5 s for an answer before its next package
    // (answer_wait_s): a host's stall of the control thread is not a lost link.
    std::vector<std::string> options{
        "robot_ip=127.0.0.1", "rtde_port=" + std::to_string(emulator.rtdePort()),
        "script_port=" + std::to_string(emulator.scriptPort()), "link_timeout_s=0.6"};
    options.insert(options.end(), extra_options.begin(), extra_options.end());
    return host::makeHardware("ur", config, host::backendContext(config, kUrPeriodS, options));
  }

  host::HardwareBackend backend;
  pipeline::CartesianWrapper wrapper;
  hardware::ControlLoop loop;
  std::jthread thread;
};

}  // namespace comply::ur::test
