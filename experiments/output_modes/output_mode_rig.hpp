#pragma once
// A controller on a simulated arm whose drives take its output.mode, run cycle by cycle through
// what a control loop does: read (with the wrist sensor), cycle, writeCommand, step. The output
// modes' experiment and tests drive it directly, so that they can push, step and read the plant
// between cycles.

#include <Eigen/Geometry>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::experiments {

inline constexpr double kRigPeriodS = 0.001;

/// config/sim/<cartesian_impedance|joint_impedance>.yaml on `robot` with output.mode `mode`.
pipeline::WrapperConfig outputModeConfig(const std::string& robot, OutputMode mode,
                                         bool cartesian = true);

/// A plant whose drives take `actuation`.
sim::PlantOptions plantOf(OutputMode actuation);

/// The plant and a wrapper on it, activated where the plant starts (home).
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

  /// One control cycle; false when the wrapper is not active afterwards or the plant refused the
  /// command.
  bool cycle() {
    read();
    const bool wrote = wrapper.cycle(state, kRigPeriodS, command);
    const bool taken = wrote && plant.writeCommand(command);
    plant.step();
    return taken && wrapper.diagnostics().state == pipeline::WrapperState::kActive;
  }

  sim::SimulatedRobot plant;
  pipeline::Wrapper<Command> wrapper;
  JointState state;
  ActuatorCommand command;
};

}  // namespace comply::experiments
