#pragma once
// Output modes position and velocity: admittance. The law runs on a virtual arm (q_v, dq_v)
// instead of the measured one; its torque, plus the wrist sensor's wrench
// (Controller::sensorWrench: the declared tool's weight and the tare off) mapped to the joints,
// accelerates the virtual arm,
//   (M(q_v) + J^T A J) ddq_v = tau_law(q_v, dq_v) + J(q_v)^T w_ext,
// where A is the inertia added at the TCP (output.admittance.added_*, task frame). The virtual arm
// has no gravity, friction or Coriolis force; the arm's own position or velocity control carries
// those. At rest the law's spring balances the external wrench, so the arm renders the commanded
// stiffness, whatever the inertia. Semi-implicit Euler, one step per cycle, then the bounds:
// joint acceleration, joint speed (a share of the URDF limit), the URDF position limits.
//
// Drift: the virtual arm is kept within max_tracking_error_rad of the measured one per joint (an
// arm blocked by a wall or lagging its command cannot wind the virtual arm up); in velocity mode
// the command adds velocity_correction_per_s (q_v - q), so the drives' own integration error does
// not accumulate. FAULT holds the measured position of the fault's first cycle (the virtual arm
// waits there); a non-finite state passes to the controller, which faults on it.
//
// Real-time: no allocation, no locks, no throw.

#include <Eigen/Cholesky>

#include "comply/core/actuator_command.hpp"
#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class Controller;

class VirtualArm {
 public:
  explicit VirtualArm(const ResolvedController& resolved);

  /// Activation: the virtual arm starts at `state`, at rest.
  void reset(const JointState& state) noexcept;
  /// The state the law runs on this cycle: the virtual arm kept near `measured` (with the sensor's
  /// raw reading), or `measured` itself when it is not usable, so that the controller faults on it.
  const JointState& lawState(const JointState& measured) noexcept;
  /// After a cycle of the law: its torque (command.effort) and the sensed wrench move the virtual
  /// arm one step, which the drives follow (command.position, command.velocity).
  void step(const Controller& controller, const JointState& measured, double period_s,
            ActuatorCommand& command) noexcept;
  /// In FAULT: the measured position of the fault's first cycle, held.
  void hold(const JointState& measured, ActuatorCommand& command) noexcept;
  /// The virtual arm the law ran on in the last cycle (position, velocity).
  [[nodiscard]] const JointState& state() const noexcept { return virtual_; }

 private:
  void keepNearMeasured(const JointState& state) noexcept;
  void integrate(const Controller& controller, double period_s,
                 const ActuatorCommand& command) noexcept;
  void addInertia(const Controller& controller) noexcept;
  void addPayload(const model::Data& data, bool sensed) noexcept;
  void writeMotion(const JointState& state, ActuatorCommand& command) const noexcept;

  const CycleParameters& parameters_;
  int dof_ = 0;
  bool velocity_mode_ = false;  ///< output.mode velocity: the drives take a velocity
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
