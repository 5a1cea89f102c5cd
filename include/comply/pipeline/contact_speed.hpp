#pragma once
// Stage "contact speed": the TCP no faster, along its direction of motion, than an unexpected
// contact there may cost (power and force limiting in the spirit of ISO/TS 15066; contact_speed.*,
// body_regions.hpp). Off by default, and one branch while off. Cartesian laws with torque or
// joint_pd output only: resolving refuses a joint law (no TCP to bound) and the admittance modes
// (position or velocity drives push through a contact with their servo's stiffness, not with the
// arm's inertia, so the energy model below does not hold for them; bound their speed with
// governor.tcp_speed_m_per_s instead).
//
// Model (ISO/TS 15066 Annex A.3): a TCP moving at speed v along u meets a body region of
// stiffness k. Its kinetic energy along u, (1/2) mu(u) v^2, goes into the region's spring,
// (1/2) F^2 / k, so the peak force is F = v sqrt(mu(u) k) and the speed that keeps it under the
// region's limit F_max is
//
//   v_max(u) = F_max / sqrt(mu(u) k),   mu(u) = (u^T Lambda_v^-1 u)^-1 + m_payload,
//   Lambda_v^-1 = J_v (M + diag(armature))^-1 J_v^T
//
// with J_v the translational rows of the TCP's Jacobian and M the arm's joint-space inertia, both
// at this cycle's pose (the model the cycle computes anyway for the Cartesian law), so that mu(u)
// is the mass that actually meets the contact in that direction at that pose, not a lumped
// constant: on the FR3 it ranges from about 2 kg to far above 10 kg across directions and poses.
// The rotor inertias (robot.yaml joint_dynamics.armature) are in the laws' M already (the model's
// ModelOptions::armature), which is the M read here. A contact must stop them too:
// left out, mu is too small and v_max too fast, i.e. unsafe (on the FR3 at home, 0.195 kg m^2 on
// joints 1 to 4 roughly doubles mu along most directions). The declared payload
// (compensation.payload.mass_kg) is added as a point mass at the TCP. By default mu is the arm's
// alone: a body part clamped against a fixed surface takes all of it, the conservative case.
// contact_speed.body_mass counts the region's effective mass m_H (Table A.3) as well, the reduced
// mass (1/m_H + 1/mu)^-1 of a free body part: faster, and less conservative.
//
// Limiting, as the motion governor's TCP part (motion_governor.hpp), with v_max(u) in place of a
// fixed speed, u = v / |v| the measured TCP velocity's direction:
//   - while the law's torque accelerates the TCP along u (its share of the acceleration,
//     u^T J_v (M + diag(armature))^-1 tau_law, is positive), that torque is scaled by a share that
//     falls linearly from 1 at 0.5 v_max to 0 at 0.85 v_max, its direction kept: the law never
//     pushes toward a contact harder than it did, and a law braking along u is never scaled;
//   - past 0.85 v_max the TCP is braked along -u, F = -(mu / 2T) (|v| - 0.85 v_max) u through
//     J_v^T, within the effort limits, its direction kept (wrench_bound.hpp): half of deadbeat on
//     the very mass along u that the force accelerates, stable on every heavier one.
// The 15 % between 0.85 v_max and v_max is the margin for what the energy model leaves out (the
// law's own push during the contact, the lag of a rate-limited torque). Slower than 0.5 v_max, or
// than 1 mm/s (a direction of noise), nothing changes: the torque is the law's, bit for bit.
//
// What it does not cover: the speed is the TCP's own point; a tool's other points (its tip while
// it turns) and the arm's links move at other speeds, and contacts there are not bounded. The
// stage runs after the motion governor (a fixed speed bound) and before the walls' barrier.
//
// Real-time: allocates nothing, takes no lock, never throws.

#include <array>
#include <cstddef>

#include "comply/core/capacity.hpp"
#include "comply/core/commands.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

/// The inertia a contact at the TCP meets at one pose: the links' joint-space inertia M plus the
/// rotors' (diag(armature)), factorised once per cycle, M + diag(armature) = L D L^T (unit lower
/// L, no square roots; its loops unrolled for 6 and 7 joints: the chain of divisions is the
/// cycle's cost, and the fixed strides let the compiler keep L in registers). Real-time: inline
/// storage, no allocation.
class ReflectedInertia {
 public:
  /// Factorises at the pose of `data` (mass matrix computed); false where it is not positive
  /// definite (a model without mass), and mass() is then infinite.
  bool factorise(const model::Data& data, const JointVector& armature, int dof) noexcept;
  /// The mass a force along `direction` (unit, base frame) at the TCP meets [kg]:
  /// (u^T J_v (M + diag(armature))^-1 J_v^T u)^-1, J_v the Jacobian's translational rows.
  /// Infinite where the arm cannot move along it (J_v^T u = 0).
  double mass(const model::Data& data, const Eigen::Vector3d& direction) noexcept;
  /// What `torque` adds to the TCP's acceleration along the last mass()'s direction [m/s^2]:
  /// u^T J_v (M + diag(armature))^-1 torque.
  [[nodiscard]] double accelerationAlong(const JointVector& torque) const noexcept;

  /// Row-major kMaxDof x kMaxDof: L's strictly lower triangle (its diagonal is 1).
  using Lower = std::array<double, static_cast<std::size_t>(kMaxDof) * kMaxDof>;

 private:
  int dof_ = 0;
  bool factorised_ = false;
  Lower lower_{};
  std::array<double, kMaxDof> inverse_pivot_{};  // 1 / D_jj
  std::array<double, kMaxDof> along_{};          // L^-1 J_v^T u
};

/// ReflectedInertia at one pose, for one direction [kg] (tests, tools; not the cycle's path).
double reflectedMass(const model::Data& data, const JointVector& armature, int dof,
                     const Eigen::Vector3d& direction);

class ContactSpeed {
 public:
  /// `cartesian`: the law takes Cartesian commands (the cycle computes the TCP's Jacobian).
  ContactSpeed(const CycleParameters& parameters, int dof, bool cartesian);

  [[nodiscard]] bool enabled() const noexcept { return enabled_; }
  void reset() noexcept;
  /// A cycle in which no law ran (FAULT's hold): the stage scaled and braked nothing; its last
  /// limit stays reported.
  void hold() noexcept {
    share_ = 1.0;
    brake_n_ = 0.0;
  }

  /// Bounds the TCP moving at `tcp_twist` (J dq) at the pose of `data` (Jacobian and mass matrix
  /// computed): the law's share of the torque, `law_torque`, is scaled in both it and `torque`,
  /// and braking is added to `torque`. True when either acted.
  bool apply(const model::Data& data, const Vector6d& tcp_twist, double period_s,
             JointVector& law_torque, JointVector& torque) noexcept;

  /// The last cycle's speed limit along the TCP's direction of motion [m/s] (the last direction
  /// it moved in faster than 1 mm/s; 0 before it has), the mass that set it [kg] (the payload
  /// and, with body_mass, the region's counted), the share of the law's torque let through and
  /// the braking force along -u [N] (0: not braking).
  [[nodiscard]] double limit() const noexcept { return limit_m_per_s_; }
  [[nodiscard]] double mass() const noexcept { return mass_kg_; }
  [[nodiscard]] double share() const noexcept { return share_; }
  [[nodiscard]] double brakeForce() const noexcept { return brake_n_; }

 private:
  bool brake(const model::Data& data, const Eigen::Vector3d& direction, double speed,
             double mass_kg, double period_s, JointVector& torque) noexcept;

  const ContactSpeedParameters& parameters_;
  const JointVector& effort_limit_;
  int dof_ = 0;
  bool enabled_ = false;
  ReflectedInertia inertia_;
  // The last cycle's, for the state.
  double limit_m_per_s_ = 0.0;
  double mass_kg_ = 0.0;
  double share_ = 1.0;
  double brake_n_ = 0.0;
};

}  // namespace comply::pipeline
