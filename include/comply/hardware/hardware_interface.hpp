#pragma once
// What a control loop talks to: a real arm's driver, a simulator or a test double. One cycle is
// read() -> controller -> write(); both calls are real-time (no allocation, no locks a
// non-real-time thread holds, no throw).

#include <span>
#include <string>

#include "comply/core/actuator_command.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"

namespace comply::hardware {

class HardwareInterface {
 public:
  virtual ~HardwareInterface() = default;

  /// Number of controlled joints, in the order of the controller's `joints`.
  [[nodiscard]] virtual int dof() const noexcept = 0;
  /// Measured joint position [rad | m], velocity [rad/s | m/s] and effort [N m | N], each dof()
  /// long. Returns false when no valid measurement exists (the caller must not run the law).
  virtual bool read(JointState& state) noexcept = 0;
  /// Joint effort command [N m | N], dof() long. Returns false when the hardware refused it.
  virtual bool write(std::span<const double> torque) noexcept = 0;

  /// Which kinds of command the drives take (actuator_command.hpp). A controller whose
  /// `output.mode` the hardware does not accept is refused before the first cycle.
  [[nodiscard]] virtual bool accepts(OutputMode mode) const noexcept {
    return mode == OutputMode::kTorque;
  }
  /// One cycle's command in any accepted mode. The default passes a torque to write() and refuses
  /// every other mode; a backend with position, velocity or per-joint PD drives overrides it.
  virtual bool writeCommand(const ActuatorCommand& command) noexcept {
    if (command.mode != OutputMode::kTorque) {
      return false;
    }
    return write({command.effort.data(), static_cast<std::size_t>(command.effort.size())});
  }

  /// No controller output this cycle (inactive, not yet activated, deactivated): hold the arm
  /// as the robot's own brake or position hold does, instead of leaving the last torque on the
  /// motors. Called each such cycle in place of write(); the next write() releases it. False
  /// when the robot has no such mode (its driver's own behaviour applies then).
  virtual bool hold() noexcept { return false; }

  /// True when the robot adds its own gravity compensation to the torque it is sent (Franka, KUKA
  /// and UR controllers do): the host then turns the wrapper's off, so it is not added twice.
  [[nodiscard]] virtual bool compensatesGravity() const noexcept { return false; }
  /// A wrist force/torque measurement [N, N m], base frame, force first, about the TCP: the
  /// wrench on the tool from all but the arm, as the sensor reads it (the tool's weight and the
  /// sensor's offset in it; the cycle takes off the declared tool's weight and a tare). False
  /// when the robot has no such sensor or no valid reading this cycle. The control loop calls it
  /// after every read() and hands it on in JointState::wrench.
  virtual bool readWrench(Vector6d& wrench) noexcept {
    (void)wrench;
    return false;
  }
  /// The driver's counter of the sample read() returned, advancing with every new sample (a
  /// sequence number or the robot's own sample time in ticks, as libfranka, RTDE and FRI give
  /// one). With it the controller knows a stale stream at once, even one that repeats a pose the
  /// arm has left while it is pushed; without it (false) it judges from the samples themselves.
  /// The control loop calls it after every read() and hands it on in JointState::sequence.
  virtual bool readSequence(std::uint64_t& sequence) noexcept {
    (void)sequence;
    return false;
  }
  /// Why the robot does not take commands now, where its controller can stop by itself (a
  /// protective or an emergency stop, its program ended, the link to it lost); nullptr while it
  /// does. The text is the backend's and stays valid until the next read(). The control loop
  /// calls it after every read() and hands it on in JointState::robot_stop. read() still returns
  /// the last state it has, so that the controller holds what it knows.
  [[nodiscard]] virtual const char* robotStop() noexcept { return nullptr; }
  /// The contact the controller lets through now before its own contact reflex trips: the
  /// largest force [N] and torque [N m] along any task axis (the file's thresholds, or a
  /// command's for its phase). A robot with collision reflexes of its own keeps them above it, so
  /// that contact the task intends does not stop the robot, and comply's reflex (a hold, a
  /// retreat) acts first. Called after every cycle while the controller has a contact reflex.
  /// Real-time.
  virtual void allowContact(double force_n, double torque_n_m) noexcept {
    (void)force_n;
    (void)torque_n_m;
  }
  /// Runs the robot's own recovery from a stop, where it has one that a client may start
  /// (libfranka's automatic error recovery after a reflex), and waits for it: "" when the robot
  /// takes commands again or had nothing to recover from, else why not. Not real-time: the live
  /// host calls it from its request thread when a reset is asked for, before the controller
  /// decides the reset (which stays refused while robotStop() is set).
  [[nodiscard]] virtual std::string recover() { return {}; }
  /// What the driver counted over the run (packages, gaps, reconnections), for the host's closing
  /// lines; "" when it has nothing to say. Not real-time: called after the loop.
  [[nodiscard]] virtual std::string summary() const { return {}; }
};

}  // namespace comply::hardware
