#pragma once
// Shared set-up of the output-mode tests: a Cartesian impedance on a plant of a given actuation,
// run cycle by cycle through the same read -> cycle -> writeCommand -> step a control loop does.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "sim_support.hpp"

namespace comply::testing {

inline constexpr double kOutputPeriodS = 0.001;

/// The task frame of the identification: turned about two axes, so that no task axis is a base
/// axis.
inline Eigen::Quaterniond turnedTaskFrame() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
}

/// config/sim/cartesian_impedance.yaml on `robot` with output.mode `mode`, task-frame stiffness
/// diag(translational, rotational) in turnedTaskFrame().
inline pipeline::WrapperConfig outputModeConfig(const std::string& robot, OutputMode mode,
                                                const Eigen::Vector3d& translational,
                                                const Eigen::Vector3d& rotational) {
  pipeline::WrapperConfig config = simCartesianConfig(robot);
  config.output.mode = mode;
  config.initial_cartesian.task_frame = turnedTaskFrame();
  config.initial_cartesian.stiffness_translational = translational.asDiagonal();
  config.initial_cartesian.stiffness_rotational = rotational.asDiagonal();
  return config;
}

/// config/sim/joint_impedance.yaml on `robot` with output.mode `mode`.
inline pipeline::WrapperConfig jointOutputModeConfig(const std::string& robot, OutputMode mode) {
  pipeline::WrapperConfig config = host::simControllerConfig(
      robot, "", (kSourceDir / "config" / "sim" / "joint_impedance.yaml").string());
  config.output.mode = mode;
  return config;
}

/// A plant of `actuation` and a wrapper on it, activated at home.
template <typename Command = CartesianCommand>
struct OutputModeRig {
  OutputModeRig(const pipeline::WrapperConfig& config, const sim::PlantOptions& options)
      : plant(*config.robot_description, options), wrapper(config) {
    state = JointState::zero(wrapper.dof());
    command.resize(wrapper.dof());
    read();
    wrapper.activate(state);
  }

  void read() {
    plant.read(state);
    state.wrench_valid = plant.readWrench(state.wrench);
  }

  /// One control cycle; false when the wrapper faulted or the plant refused the command.
  bool cycle() {
    read();
    const bool wrote = wrapper.cycle(state, kOutputPeriodS, command);
    const bool taken = wrote && plant.writeCommand(command);
    plant.step();
    return taken && wrapper.diagnostics().state == pipeline::WrapperState::kActive;
  }

  sim::SimulatedRobot plant;
  pipeline::Wrapper<Command> wrapper;
  JointState state;
  ActuatorCommand command;
};

inline sim::PlantOptions plantOf(OutputMode actuation) {
  sim::PlantOptions options;
  options.actuation = actuation;
  return options;
}

}  // namespace comply::testing
