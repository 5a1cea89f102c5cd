#pragma once
// A wrapper on a simulated arm, run as the control loop runs it (the hardware's hold when the
// wrapper asks for it), keeping the fastest joint over its URDF limit and the TCP's speed: what
// the stop-means-stop tests and the governor sweep measure.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::testing {

using pipeline::WrapperState;

/// The wrapper on the plant, as the control loop runs it (the hardware's hold when asked for).
template <typename Command = CartesianCommand>
struct Arm {
  explicit Arm(const pipeline::WrapperConfig& config) : Arm(config, sim::PlantOptions{}, {}) {}
  /// The plant built with `options` (its actuation the config's output mode), the arm put at
  /// `start` (joint positions) at rest first when given.
  Arm(const pipeline::WrapperConfig& config, sim::PlantOptions options,
      const std::vector<double>& start)
      : plant(*config.robot_description, withActuation(options, config.output.mode)),
        wrapper(config) {
    state = JointState::zero(wrapper.dof());
    command.resize(wrapper.dof());
    if (!start.empty()) {
      plant.setJointPositions(start);
    }
    plant.read(state);
    wrapper.activate(state);
    start_tcp = wrapper.measuredPose().tcp_position;
  }

  /// One cycle; the largest joint speed over its URDF limit and the TCP speed are kept. With
  /// `bad_sample`, the wrapper reads a NaN joint position this cycle (a FAULT).
  void cycle(bool bad_sample = false) {
    plant.read(state);
    JointState read = state;
    if (bad_sample) {
      read.position[0] = std::nan("");
    }
    if (wrapper.cycle(read, plant.controlPeriod(), command)) {
      plant.writeCommand(command);
      if (brakes && wrapper.wantsHold()) {
        held = plant.hold() || held;
      }
    }
    plant.step();
    const model::Model& model = wrapper.controller().model();
    double ratio = 0.0;
    for (int i = 0; i < wrapper.dof(); ++i) {
      ratio = std::max(ratio, std::abs(state.velocity[i]) / model.limits(i).velocity);
    }
    worst_ratio = std::max(worst_ratio, ratio);
    const Eigen::Vector3d tcp = wrapper.measuredPose().tcp_position;
    worst_tcp_speed = std::max(worst_tcp_speed, (tcp - last_tcp).norm() / plant.controlPeriod());
    last_tcp = tcp;
  }

  static sim::PlantOptions withActuation(sim::PlantOptions options, OutputMode mode) {
    options.actuation = mode;
    return options;
  }

  [[nodiscard]] bool faulted() const { return wrapper.diagnostics().state == WrapperState::kFault; }
  [[nodiscard]] Eigen::Vector3d tcp() const { return wrapper.measuredPose().tcp_position; }
  [[nodiscard]] double fastestJoint() const { return state.velocity.cwiseAbs().maxCoeff(); }

  sim::SimulatedRobot plant;
  pipeline::Wrapper<Command> wrapper;
  JointState state;
  ActuatorCommand command;
  Eigen::Vector3d start_tcp;
  Eigen::Vector3d last_tcp = Eigen::Vector3d::Constant(std::nan(""));
  double worst_ratio = 0.0;
  double worst_tcp_speed = 0.0;
  bool held = false;
  bool brakes = true;  ///< the plant's hold when the wrapper asks for it (false: torques alone)
};

/// A stiff target `offset_m` from the measured TCP, rotated by `angle_rad` about base z, at
/// `stiffness_n_per_m` (and 4000 N m/rad when it turns, else 200).
inline CartesianCommand stiffStep(const Arm<>& arm, const Eigen::Vector3d& offset_m,
                                  double angle_rad, double stiffness_n_per_m = 1e4) {
  CartesianCommand target = CartesianCommand::zero(arm.wrapper.dof());
  target.stamp_s = 1.0;
  target.fields = CommandField::kPosition | CommandField::kStiffness;
  const MeasuredPose measured = arm.wrapper.measuredPose();
  target.position = measured.tcp_position + offset_m;
  target.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ())) *
                       measured.tcp_orientation;
  target.stiffness_translational = stiffness_n_per_m * Eigen::Matrix3d::Identity();
  target.stiffness_rotational = (angle_rad == 0.0 ? 200.0 : 4000.0) * Eigen::Matrix3d::Identity();
  return target;
}

}  // namespace comply::testing
