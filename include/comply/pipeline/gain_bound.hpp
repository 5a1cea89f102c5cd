#pragma once
// The gains an arm renders stably at its control period, and through its torque-rate limit.
//
// Model. One inertia m (the arm's lightest along the gain, below), a spring K and a damper D
// (w_n = sqrt(K / m), zeta = D / (2 sqrt(K m))). The law's torque u_k = -K x_k - D v_k is computed
// from the sample at t_k = k T, moves by at most R T from u_(k-1) (the torque-rate limit R,
// torque_rate_limit_nm_per_s), and is held for one period, applied one period later on a real
// driver (in simulation at once).
//
// 1. Sampled loop (no rate limit). Its z-domain poles stay inside the unit circle only while
//    w_n T < 0.43 when critically damped (0.49 at zeta 0.7, 0.24 at 2, docs/safety.md) and
//    D T / m < 1. Beyond that a command inside every fixed limit (1e6 N/m) rings up until the
//    joints saturate. Bound: w_n T <= c, c = validation.max_wn_period (0.35, a 20 % margin):
//
//      stiffness               K <= m (c / T)^2       (its stiffest axis, the largest eigenvalue)
//      damping (absolute)      D <= 2 c m / T         (what critical damping needs at that K)
//      damping (ratio)         zeta sqrt(K / m) T <= c
//
// 2. Through the rate limit. A linearly stable loop can still lock into a limit cycle at the rate
//    limit: the FR3's wrist at 2000 N m/rad (w_n T = 0.22; its damping then a twenty-fifth of
//    critical, the laws' M without the rotors) stepped its torque by the full 1 N m a cycle at
//    14 to 56 Hz, and was stable without the limit. The limiter's describing function depends
//    on rho = R / (A w) alone (A, w: the amplitude and frequency of the law's torque): gain 1 and
//    no lag for rho >= 1, then down to 4 rho / pi and 90 deg of lag (rho 0.5: 0.64, -38 deg;
//    0.3: 0.38, -62 deg). The loop (K + D s) e^(-s T_d) / (m s^2) meets -1 / N(rho) near w_n, at
//    rho* w* = w_n / kappa: an oscillation of the law's torque below A* = kappa R / w_n dies out,
//    one above it grows into the cycle (an unstable limit cycle; a step's swing counts as its
//    amplitude). kappa from the describing function and from the sampled loop itself agree within
//    10 %; the sampled loop's (tests/pipeline/gain_bound_rate_test.cpp checks them):
//
//      zeta      no delay (w_n T 0.05-0.2)   one period of delay (w_n T 0.05 / 0.1 / 0.2)
//      0.2       1.6-1.8                     1.65 / 1.51 / 1.19
//      0.7       2.7-2.9                     2.60 / 2.31 / 1.69
//      1.0       3.3-3.7                     3.23 / 2.75 / 1.85
//      1.5       4.5-4.9                     4.08 / 3.27 / 1.65
//
//    kappa >= 1.19 from zeta 0.2 to 1.5 within the sampled bound (below 0.2, or with the damping
//    of part 1 used up, the sampled loop itself is the limit). So, with tau =
//    validation.rate_limit_swing_nm (5 N m) the swing of the law's torque to pass linearly:
//
//      stiffness               sqrt(K / m) <= R / tau,  K <= m (R / tau)^2
//
//    with R the lowest joint's rate for a Cartesian gain (its torque reaches every joint; the
//    lever from force to joint torque scales the swing and the rate alike) and joint i's for a
//    joint or nullspace gain. At 1000 N m/s and 5 N m that is w_n <= 200 rad/s, w_n T <= 0.2 at
//    1 kHz. Only output.mode torque: the drives' own PD (joint_pd) and the virtual arm (position,
//    velocity) are not rate limited by comply. A step of K dx above tau is not refused: it is
//    shaped by the rate limit and dies out while below A* (simulation, docs/safety.md).
//
// comply bounds each gain by the arm's lightest inertia along it, found once per controller over
// the workspace (the rotor inertias the robot declares included, as the laws' M(q) has them),
// with w_n <= min(c / T, R / tau): m the lightest apparent mass at the TCP for the translational
// blocks, the lightest apparent rotational inertia for the rotational ones, and each joint's
// lightest inertia for joint gains and the nullspace's. A command above a bound is refused
// (invalid_gains) with the numbers and the part that bound it. Per output mode
// (docs/output-modes.md), T is the cycle's period in each:
//
//   torque     the arm's inertia (rotor inertias included), both parts.
//   joint_pd   part 1 as torque (the nullspace spring and a Cartesian law's couplings stay in the
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
//
// A robot that declares no rotor inertias (robot.yaml joint_dynamics.armature) is bounded the
// same way, along translation only (bare_links), and resolveController() warns: its bare wrist
// is not a geared arm's (a Gen3-like arm's 5e-4 kg m^2 against 0.03 with rotors), and the bound
// would refuse every default rotational stiffness on it.

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
  /// [N m/s] each joint's torque-rate limit R_i, which the law's torque passes through (output.mode
  /// torque); empty: no rate bound.
  JointVector torque_rate_limit;
  double rate_limit_swing_nm = 5.0;  ///< tau above [N m]; 0: no rate bound
  /// The inertias are bare links' (the virtual arm; a robot that declares no rotor inertias):
  /// rotational_inertia_kg_m2 and joint_inertia are then infinite (not bounded).
  bool bare_links = false;
  std::string robot;  ///< named in the messages

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
