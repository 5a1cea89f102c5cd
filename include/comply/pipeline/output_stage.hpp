#pragma once
// The last stage of a cycle: what the drives receive (output.mode; core/actuator_command.hpp).
// One law and one command schema serve arms of every kind:
//
//   torque    the cycle's torque, as it is.
//   joint_pd  the same torque split for a drive with an onboard PD (output/joint_pd.cpp):
//             kp (q_d - q) + kd (dq_d - dq) + tau_ff equals it exactly at the sample. Between
//             samples the drive's PD adds the diagonal of the law's own stiffness and damping
//             around the sample: exact for the joint law's diagonal gains; for the Cartesian law
//             the diagonal of J^T K J (and J^T D J), approximate (see the file).
//   position  admittance (virtual_arm.hpp): the law runs on a virtual arm, whose motion
//   velocity  under the law's torque and the measured external wrench the drives follow.
//
// The controller owns it and runs it in its cycle() (controller.hpp): lawState() before the
// law's cycle, write() after it. Real-time: no allocation, no locks, no throw.

#include <Eigen/Geometry>

#include "comply/core/actuator_command.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/cycle_status.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/virtual_arm.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {

class Controller;

/// The task frame of a Cartesian bus as a rotation into the base frame.
inline Eigen::Matrix3d taskToBase(const comply_cartesian_command& bus) noexcept {
  return schema::fromXyzw(bus.task_frame).normalized().toRotationMatrix();
}

class OutputStage {
 public:
  explicit OutputStage(const ResolvedController& resolved);

  [[nodiscard]] OutputMode mode() const noexcept { return parameters_.output.mode; }
  /// Activation: an admittance's virtual arm starts at `state`.
  void reset(const JointState& state) noexcept { arm_.reset(state); }
  /// The state the law runs on this cycle: an admittance's virtual arm, else `measured`.
  const JointState& lawState(const JointState& measured) noexcept;
  /// After the law's cycle (`status`, its torque in command.effort): the command for the drives;
  /// false when the controller is inactive (nothing to write).
  bool write(CycleStatus status, const Controller& controller, const JointState& measured,
             double period_s, ActuatorCommand& command) noexcept;
  /// Admittance: the virtual arm the law ran on in the last cycle (position, velocity).
  [[nodiscard]] const JointState& virtualState() const noexcept { return arm_.state(); }

 private:
  // output/joint_pd.cpp
  void splitForJointPd(const Controller& controller, bool fault, const JointState& state,
                       ActuatorCommand& command) const noexcept;
  void cartesianJointGains(const Controller& controller, const JointState& state,
                           ActuatorCommand& command) const noexcept;

  const CycleParameters& parameters_;
  int dof_ = 0;
  bool cartesian_ = false;
  VirtualArm arm_;
};

}  // namespace comply::pipeline
