#include "comply/pipeline/wrapper.hpp"

#include "comply/pipeline/command_bus.hpp"

namespace comply::pipeline {
namespace {

const JointCommand& initialCommand(const WrapperConfig& config, const JointCommand*) {
  return config.initial_joint;
}
const CartesianCommand& initialCommand(const WrapperConfig& config, const CartesianCommand*) {
  return config.initial_cartesian;
}

void anchorBus(comply_joint_command& bus, const comply_input& input) {
  for (int i = 0; i < input.dof; ++i) {
    bus.position[i] = input.position[i];
    bus.velocity[i] = 0.0;
    bus.acceleration[i] = 0.0;
  }
}
void anchorBus(comply_cartesian_command& bus, const comply_input& input) {
  for (int k = 0; k < 3; ++k) {
    bus.position[k] = input.tcp_position[k];
  }
  for (int k = 0; k < 4; ++k) {
    bus.orientation[k] = input.tcp_orientation[k];
  }
  for (int k = 0; k < 6; ++k) {
    bus.twist[k] = 0.0;
    bus.acceleration[k] = 0.0;
  }
  // As seedReference(): the re-anchored controller holds the measured joints in the nullspace too,
  // instead of pulling the elbow back to where the last command left it.
  for (int i = 0; i < input.dof; ++i) {
    bus.nullspace_position[i] = input.position[i];
  }
}

/// Holding the last reference means holding its pose: a velocity reference would keep pulling.
void stopMotion(comply_joint_command& bus) {
  for (int i = 0; i < COMPLY_MAX_DOF; ++i) {
    bus.velocity[i] = 0.0;
    bus.acceleration[i] = 0.0;
  }
}
void stopMotion(comply_cartesian_command& bus) {
  for (int k = 0; k < 6; ++k) {
    bus.twist[k] = 0.0;
    bus.acceleration[k] = 0.0;
  }
}
void stopMotion(JointCommand& command) {
  command.velocity.setZero();
  command.acceleration.setZero();
}
void stopMotion(CartesianCommand& command) {
  command.twist.setZero();
  command.acceleration.setZero();
}

}  // namespace

void seedReference(JointCommand& command, const MeasuredPose& pose) {
  command.position = pose.position;
  command.velocity.setZero(pose.position.size());
  command.acceleration.setZero(pose.position.size());
}
void seedReference(CartesianCommand& command, const MeasuredPose& pose) {
  command.position = pose.tcp_position;
  command.orientation = pose.tcp_orientation;
  command.twist.setZero();
  command.acceleration.setZero();
  command.nullspace_position = pose.position;
}

template <typename Command>
Wrapper<Command>::Wrapper(const WrapperConfig& config)
    : core_(config, CommandTraits<Command>::kKind),
      merged_(initialCommand(core_.config(), static_cast<const Command*>(nullptr))) {
  merged_.fields = CommandField::kAll;
  bus_.write(toBus(merged_, core_.dof()));
}

template <typename Command>
void Wrapper<Command>::activate(const JointState& state) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  core_.deactivate();
  const MeasuredPose pose = core_.prepareActivation(state);
  Command seeded = merged_;
  seedReference(seeded, pose);
  const Bus bus = toBus(seeded, core_.dof());
  core_.activate(&bus);  // throws before anything changes if the law refuses
  merged_ = seeded;
  active_ = bus;
  bus_.write(bus);
  anchor_.update();              // drop an anchor from before the deactivation
  motion_stopped_.store(false);  // and a stop likewise
}

template <typename Command>
void Wrapper<Command>::deactivate() noexcept {
  core_.deactivate();
}

template <typename Command>
Verdict Wrapper<Command>::submit(const Command& command) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  if (anchor_.update()) {
    // The watchdog re-anchored the cycle; later partial commands build on that reference.
    seedReference(merged_, anchor_.read());
  }
  if (motion_stopped_.exchange(false)) {
    // The watchdog stopped the motion reference; a partial command must not revive it.
    stopMotion(merged_);
  }
  const MeasuredPose measured = core_.measuredPose();
  Verdict verdict =
      validateAndMerge(command, core_.config().validation, core_.dof(), measured, merged_);
  Diagnostics& diagnostics = core_.diagnostics();
  if (!verdict.accepted) {
    diagnostics.rejections[static_cast<std::size_t>(verdict.reason)].fetch_add(1);
    diagnostics.setError("command rejected: ", verdict.message.c_str());
    return verdict;
  }
  diagnostics.commands_accepted.fetch_add(1);
  bus_.write(toBus(merged_, core_.dof()));
  return verdict;
}

template <typename Command>
Command Wrapper<Command>::lastAccepted() const {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  return merged_;
}

template <typename Command>
void Wrapper<Command>::reanchor() noexcept {
  anchorBus(active_, core_.input());
  MeasuredPose pose;
  const comply_input& input = core_.input();
  pose.position.resize(input.dof);
  for (int i = 0; i < input.dof; ++i) {
    pose.position[i] = input.position[i];
  }
  pose.tcp_position =
      Eigen::Vector3d(input.tcp_position[0], input.tcp_position[1], input.tcp_position[2]);
  pose.tcp_orientation = Eigen::Quaterniond(input.tcp_orientation[3], input.tcp_orientation[0],
                                            input.tcp_orientation[1], input.tcp_orientation[2]);
  pose.valid = true;
  anchor_.publishFromSoleWriter(pose);
}

template <typename Command>
CycleStatus Wrapper<Command>::update(const JointState& state, double period_s,
                                     std::span<double> torque) noexcept {
  core_.beginCycle(state, period_s);
  if (bus_.update()) {
    active_ = bus_.read();
    core_.noteCommand();
  }
  if (core_.watchdogFired()) {
    if (core_.config().timeout_behavior == TimeoutBehavior::kReanchor) {
      reanchor();
    } else {
      stopMotion(active_);
      motion_stopped_.store(true);
    }
  }
  return core_.finishCycle(&active_, torque);
}

template class Wrapper<JointCommand>;
template class Wrapper<CartesianCommand>;

}  // namespace comply::pipeline
