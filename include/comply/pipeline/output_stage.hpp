#pragma once
// The last stage of a cycle: what the drives receive (output.mode; core/actuator_command.hpp).
// One law and one command schema serve arms of every kind:
//
//   torque    the cycle's torque, as it is.
//   joint_pd  the same torque split for a drive with an onboard PD (output_joint_pd.cpp):
//             kp (q_d - q) + kd (dq_d - dq) + tau_ff equals it exactly at the sample. Between
//             samples the drive's PD adds the diagonal of the law's own stiffness and damping
//             around the sample: exact for the joint law's diagonal gains; for the Cartesian law
//             the diagonal of J^T K J (and J^T D J), approximate (see the file).
//   position  admittance (output_admittance.cpp): the law runs on a virtual arm, whose motion
//   velocity  under the law's torque and the measured external wrench the drives follow.
//
// Real-time: no allocation, no locks, no throw.

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "comply/core/actuator_command.hpp"
#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {

/// The task frame of a Cartesian bus as a rotation into the base frame.
inline Eigen::Matrix3d taskToBase(const comply_cartesian_command& bus) noexcept {
  return schema::fromXyzw(bus.task_frame).normalized().toRotationMatrix();
}

class OutputStage {
 public:
  explicit OutputStage(const ResolvedController& resolved);

  [[nodiscard]] OutputMode mode() const noexcept { return parameters_.output.mode; }
  /// Between cycles, after the controller's activate(): the virtual arm starts at `state`.
  void activate(const JointState& state) noexcept;
  /// One cycle of `controller` and its command for the drives; false when the controller is
  /// inactive (nothing to write).
  bool cycle(Controller& controller, const JointState& state, double period_s,
             ActuatorCommand& command) noexcept;
  /// Admittance: the virtual arm the law ran on in the last cycle (position, velocity).
  [[nodiscard]] const JointState& virtualState() const noexcept { return virtual_; }

 private:
  // output_joint_pd.cpp
  void splitForJointPd(const Controller& controller, bool fault, const JointState& state,
                       ActuatorCommand& command) const noexcept;
  void cartesianJointGains(const Controller& controller, const JointState& state,
                           ActuatorCommand& command) const noexcept;
  // output_admittance.cpp
  bool admittance(Controller& controller, const JointState& state, double period_s,
                  ActuatorCommand& command) noexcept;
  void keepNearMeasured(const JointState& state) noexcept;
  void integrate(const Controller& controller, double period_s,
                 const ActuatorCommand& command) noexcept;
  void addInertia(const Controller& controller) noexcept;
  void addPayload(const model::Data& data, bool sensed) noexcept;
  void holdMeasured(const JointState& state, ActuatorCommand& command) noexcept;
  void writeMotion(const JointState& state, ActuatorCommand& command) const noexcept;

  const CycleParameters& parameters_;
  int dof_ = 0;
  bool cartesian_ = false;

  // Admittance: the virtual arm, what it holds in FAULT, and scratch for its dynamics.
  JointState virtual_;
  JointVector last_measured_;  ///< the last finite measured position
  JointVector hold_position_;
  bool holding_ = false;
  JointMatrix inertia_;
  Eigen::LDLT<JointMatrix> inertia_solver_;
  bool added_inertia_ = false;  ///< output.admittance.added_*: any entry above zero
  JointVector virtual_torque_;
  Vector6d external_ = Vector6d::Zero();  ///< the sensed wrench the virtual arm answers
  JointVector acceleration_;
};

}  // namespace comply::pipeline
