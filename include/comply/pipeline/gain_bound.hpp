#pragma once
// The gains an arm renders stably at its control period. A spring K with damping D on an inertia
// m, sampled every T with one period between the sample and the torque (a real driver's delay),
// is stable only while w_n T stays below 0.43 when critically damped (w_n = sqrt(K/m); the
// z-domain poles of the sampled loop, docs/safety.md) and D T / m below 1. Beyond that a command
// inside every fixed limit (1e6 N/m) rings up until the joints saturate.
//
// comply bounds each gain by the arm's lightest inertia along it, found once per controller over
// the workspace (the rotor inertias the robot declares included), with w_n T <= c, c =
// validation.max_wn_period (0.35, a 20 % margin):
//
//   stiffness               K <= m (c / T)^2          (its stiffest axis, the largest eigenvalue)
//   damping (absolute)      D <= 2 c m / T            (what critical damping needs at that K)
//   damping (ratio)         zeta sqrt(K / m) T <= c
//
// with m the lightest apparent mass at the TCP for the translational blocks, the lightest
// apparent rotational inertia for the rotational ones, and each joint's lightest inertia for
// joint gains and the nullspace's. A command above a bound is refused (invalid_gains) with the
// numbers. Per output mode (docs/output-modes.md), T is the cycle's period in each:
//
//   torque     the arm's inertia (rotor inertias included), as above.
//   joint_pd   as torque (the nullspace spring and a Cartesian law's couplings stay in the
//              cycle's feedforward), and the drive's own gains too: the drive runs its PD at a
//              rate comply does not know, taken as the cycle's (a faster drive renders at least
//              that). A joint law's kp, kd are the command's; a Cartesian law's are
//              kp_i = J_i^T K J_i, kd_i = J_i^T D J_i (joint_pd.cpp), bounded over the workspace
//              by k_t |J_i,linear|^2 + k_r |J_i,angular|^2 (k: each block's largest eigenvalue;
//              the largest |J_i|^2 over the samples), each against joint i's lightest inertia;
//              with damping ratios, the mean ratio on that kp (kd_i = 2 zeta sqrt(kp_i M_ii),
//              M_ii taken as the lightest inertia).
//   position,  the virtual arm the admittance law drives (virtual_arm.hpp), integrated once a
//   velocity   cycle: the arm's inertia without the rotor inertias (the virtual arm has none)
//              plus output.admittance.added_* (each block's smallest entry along every axis, the
//              task frame turns; J^T A J joined to M at every sample). Along translation only:
//              without rotors the virtual wrist is the bare links' (the FR3's lightest rotational
//              inertia 1.0e-4 kg m^2, 0.040 with its rotors), and a bound there would refuse every
//              robot's default 300 N m/rad; rotation and the joints stay unbounded (infinite
//              inertias), held by the virtual arm's own acceleration, speed and drift bounds.

#include <string>

#include "comply/core/capacity.hpp"
#include "comply/core/commands.hpp"
#include "comply/model/model.hpp"
#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline {

struct GainBound {
  /// [kg] lightest apparent mass at the TCP over the workspace; 0: no bound.
  double translational_mass_kg = 0.0;
  /// [kg m^2] lightest apparent rotational inertia at the TCP; 0: no bound.
  double rotational_inertia_kg_m2 = 0.0;
  /// [kg m^2 | kg] each joint's lightest inertia (the others free to move); empty: no bound.
  JointVector joint_inertia;
  /// [m^2 | 1] each joint's largest |J_i,linear|^2 and |J_i,angular|^2 over the workspace: what
  /// a Cartesian stiffness becomes on joint i's drive (joint_pd).
  JointVector joint_lever_sq;
  JointVector joint_axis_sq;
  /// output.mode joint_pd with a Cartesian law: the drives' kp_i, kd_i are checked too.
  bool drive_gains = false;
  double max_wn_period = 0.35;  ///< c above
  std::string robot;            ///< named in the messages

  [[nodiscard]] bool enabled() const noexcept { return joint_inertia.size() > 0; }
};

/// Inertia joined to the arm's at the TCP, isotropic: [kg] along every axis, [kg m^2] about it.
struct AddedInertia {
  double mass_kg = 0.0;
  double inertia_kg_m2 = 0.0;
};

/// The lightest inertias of `model` (plus the diagonal `armature`, in the model's joint order;
/// empty for none; plus J^T diag(added) J) over `samples` configurations drawn uniformly within
/// the joint limits (fixed seed) and the middle of the limits.
GainBound lightestInertias(const model::Model& model, const JointVector& armature,
                           int samples = 2000, AddedInertia added = {});

/// The command's gains against `bound` at control period `period_s`: accepted, or invalid_gains
/// naming the field, the value, the bound and what it comes from. Only the groups
/// `command.fields` names are checked; a damping ratio with the stiffness `command` holds, so the
/// caller passes the command merged into the gains in force (Wrapper::submit does).
Verdict checkRenderable(const CartesianCommand& command, const GainBound& bound, double period_s);
Verdict checkRenderable(const JointCommand& command, const GainBound& bound, double period_s);

}  // namespace comply::pipeline
