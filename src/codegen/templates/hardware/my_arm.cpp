// my_arm: a comply hardware backend, the arm `comply run --hardware my_arm` drives.
//
// A starting point written by `comply plugin new --kind hardware`. So that it runs before any
// robot is connected, it simulates an arm without gravity: each joint a unit inertia with viscous
// damping, moved by the commanded torque. A driver for a real robot keeps the shape of this class
// and replaces the simulation with its robot's protocol: the constructor connects, read()
// receives the measured state, write() sends the torque, the destructor stops the robot and
// disconnects.
//
// read() and write() run in the control loop, once per period each: they must not allocate,
// wait on a lock another thread holds for long, or throw. Everything slow happens in the
// constructor (or in a thread of the driver's own that the two calls exchange data with).

#include <cmath>
#include <cstddef>
#include <exception>
#include <span>
#include <stdexcept>
#include <string>

#include "comply/hardware/backend.hpp"

namespace {

/// The number `--hardware-option NAME=VALUE` gave, or `fallback` without one.
double numberOption(const comply::hardware::BackendContext& context, const std::string& name,
                    double fallback) {
  const auto found = context.options.find(name);
  if (found == context.options.end()) {
    return fallback;
  }
  const std::string& text = found->second;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument("my_arm: option " + name + "=" + text + " is not a number");
  }
  return value;
}

class MyArm final : public comply::hardware::HardwareInterface {
 public:
  /// Called once, before the first cycle, outside the control loop. A real driver connects to
  /// its robot here (its address and other settings arrive in context.options, from
  /// `--hardware-option key=value`), checks that the robot has the joints in context.joints, and
  /// throws when anything is wrong: `comply run` stops with "refused to start: <message>".
  explicit MyArm(const comply::hardware::BackendContext& context)
      : dof_(static_cast<int>(context.joints.size())), period_s_(context.period_s) {
    if (dof_ < 1 || dof_ > comply::kMaxDof) {
      throw std::invalid_argument("my_arm drives 1 to " + std::to_string(comply::kMaxDof) +
                                  " joints, the controller has " + std::to_string(dof_));
    }
    if (context.home_position.size() != context.joints.size()) {
      throw std::invalid_argument("my_arm needs a home position for every joint");
    }
    if (!(std::isfinite(period_s_) && period_s_ > 0.0)) {
      throw std::invalid_argument("my_arm needs a positive control period");
    }
    // `--hardware-option damping=0.5` sets the simulated joints' viscous damping.
    damping_nms_per_rad_ = numberOption(context, "damping", damping_nms_per_rad_);
    if (damping_nms_per_rad_ < 0.0) {
      throw std::invalid_argument("my_arm: damping must be >= 0");
    }
    // The simulated arm starts at the robot's home position, at rest.
    position_.resize(dof_);
    velocity_.setZero(dof_);
    torque_nm_.setZero(dof_);
    for (int i = 0; i < dof_; ++i) {
      position_[i] = context.home_position[static_cast<std::size_t>(i)];
    }
  }

  [[nodiscard]] int dof() const noexcept override { return dof_; }

  /// The measured state, once per cycle before the control law runs. A real driver returns the
  /// robot's latest measurement here, and false when none arrived in time: the loop then skips
  /// the law for this cycle rather than act on a stale state.
  bool read(comply::JointState& state) noexcept override {
    // One period has passed since the last read, under the torque written in between. Each joint:
    // unit inertia [kg m^2], acceleration = torque - damping * velocity, integrated by
    // semi-implicit Euler (the new velocity moves the position), which keeps a damped joint
    // stable at any period a control loop uses.
    for (int i = 0; i < dof_; ++i) {
      const double acceleration = torque_nm_[i] - damping_nms_per_rad_ * velocity_[i];
      velocity_[i] += acceleration * period_s_;
      position_[i] += velocity_[i] * period_s_;
    }
    // Inline storage (comply::JointVector): assigning resizes without allocating.
    state.position = position_;
    state.velocity = velocity_;
    state.effort = torque_nm_;  // a simulated joint exerts exactly what it is sent
    return true;
  }

  /// The torque the law computed, once per cycle after read(). A real driver sends it to the
  /// robot here, and returns false when the robot refused it (the loop counts those).
  bool write(std::span<const double> torque_nm) noexcept override {
    if (static_cast<int>(torque_nm.size()) != dof_) {
      return false;
    }
    for (int i = 0; i < dof_; ++i) {
      if (!std::isfinite(torque_nm[static_cast<std::size_t>(i)])) {
        return false;  // keep the last torque rather than send the arm a NaN
      }
    }
    for (int i = 0; i < dof_; ++i) {
      torque_nm_[i] = torque_nm[static_cast<std::size_t>(i)];
    }
    return true;
  }

  /// Whether the robot adds gravity compensation to the torque it is sent. This arm has no
  /// gravity to compensate, so it answers true: the host then leaves gravity out of the torque it
  /// computes, as it must for a robot that compensates by itself. A real driver returns what its
  /// robot does: true when the robot's own controller adds gravity to the commanded torque (as
  /// Franka's, KUKA's and UR's torque interfaces do), false when the torque goes to the motors as
  /// it is and comply's model has to supply it.
  [[nodiscard]] bool compensatesGravity() const noexcept override { return true; }

  // A robot with a wrist force/torque sensor also overrides
  //   bool readWrench(comply::Vector6d& wrench) noexcept
  // to report it (base frame, force first); the default says there is none. A driver whose robot
  // numbers its samples (a sequence counter, or the robot's own sample time in ticks) overrides
  //   bool readSequence(std::uint64_t& sequence) noexcept
  // so that a stale stream is caught at once, whatever the arm does. Drives that take a
  // position, a velocity or a per-joint PD command instead of a torque override
  //   bool accepts(comply::OutputMode mode) const noexcept
  //   bool writeCommand(const comply::ActuatorCommand& command) noexcept
  // (controllers then set output.mode: joint_pd, position or velocity).

 private:
  int dof_;
  double period_s_;
  double damping_nms_per_rad_ = 2.0;  ///< viscous damping [N m s/rad | N s/m]
  comply::JointVector position_;      ///< [rad | m]
  comply::JointVector velocity_;      ///< [rad/s | m/s]
  comply::JointVector torque_nm_;     ///< the torque last written [N m | N]
};

}  // namespace

// Exports the entry points `comply run` looks up: comply_hardware_abi_version,
// comply_hardware_create (which calls MyArm's constructor) and comply_hardware_destroy.
COMPLY_HARDWARE_BACKEND(MyArm)
