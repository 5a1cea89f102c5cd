#pragma once
// The energy tank of the gain stage (gain_guard.hpp). It pays for what a change of stiffness or
// task frame injects into the springs at the current error, dV = 1/2 e^T (K_base,new -
// K_base,old) e with K_base = R K R^T (Ferraguti et al., T-RO 2015; task_stiffness.hpp). When it
// cannot pay, the change made this cycle is scaled back to what it can pay: the gains stay where
// they are and go on as the tank refills, never falling back. A move of the nullspace target is
// paid the same way, from the nullspace account: the springs' potential change at the measured
// joints (payNullspaceMove). A decrease is always allowed; the
// energy it releases is credited only up to what the tank paid and has not had back, so a
// decrease cannot fill the tank with energy it never held. The nullspace has its own account
// (Dietrich et al., RA-L 2017).
//
// Refill. The damping dissipates at least d_min |J dq - v_d|^2 (d_min: a lower bound of the
// damping matrix), and over a window of w seconds the integral of |x'|^2 is at least
// |x(w) - x(0)|^2 / w (Cauchy-Schwarz). The tank is credited that bound, computed from position
// increments minus the commanded velocity times the time: measured velocity never enters, so
// its noise cannot create energy. With damping ratios, the damping is the law's
// D = 2 S (Lambda # K) S (# the matrix geometric mean, monotone in both arguments), bounded
// below from K, the ratios and Lambda^-1 = J M^-1 J^T, evaluated once per window and only while
// the tank is not full. The nullspace account has no refill: the projected damping's
// dissipation has no lower bound as cheap; it spends its initial energy and what decreases give
// back.
//
// What the energy is computed from: the TCP pose error against the command's pose and the task
// frame as commanded (a law that turns the frame with the measured tool, task_frame_reference:
// tcp, rotates it further; the tank then sees only the commanded part), and for the nullspace
// 1/2 sum k_i (q_ns,i - q_i)^2. Real-time: no allocation, no lock, no exception.

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/config.hpp"

namespace comply::pipeline {

struct TaskStiffness;

/// One energy account: what it holds, and what it paid and has not had back.
struct EnergyAccount {
  double energy_j = 0.0;
  double outstanding_j = 0.0;  ///< paid for increases, not yet returned by decreases
  double max_j = 0.0;
  double min_j = 0.0;

  /// The part of `injection_j` (> 0) it can pay; takes it.
  double pay(double injection_j) noexcept;
  /// A decrease released `released_j` (> 0): credits what was paid and is not back yet.
  void takeBack(double released_j) noexcept;
  /// Credits `credit_j` up to the ceiling; returns what was taken.
  double refill(double credit_j) noexcept;
  /// [J] what it can spend before the floor.
  [[nodiscard]] double spendable() const noexcept { return energy_j - min_j; }
};

/// The task account (the Cartesian task, or the joints under joint control) with its refill, the
/// nullspace account, and the totals the diagnostics show.
class EnergyTank {
 public:
  explicit EnergyTank(const PassivityConfig& passivity) noexcept;

  /// On activation: the accounts hold their initial energy, the totals are zero, no refill window
  /// is open, and increments count from the pose in `data` and the joints in `state`.
  void reset(const model::Data& data, const JointState& state) noexcept;
  /// A new cycle: what it refuses is counted afresh (a held-back change is offered again).
  void beginCycle() noexcept { refused_j_ = 0.0; }
  /// The eigenvalue bounds the refill reads, from the gains in force `law` (after they moved).
  void cacheBounds(const CommandBus& law) noexcept;

  // Paying for a change of the gains in force `law` to a candidate, at the measured state: each
  // returns the fraction (0..1) of the change its account pays, and takes that.
  /// The task stiffness and frame, from `in_force` (law's) to `candidate`.
  double payTaskChange(const comply_cartesian_command& law, const model::Data& data,
                       const TaskStiffness& in_force, const TaskStiffness& candidate) noexcept;
  /// The nullspace stiffness, to `candidate` (one entry a joint).
  double payNullspaceChange(const comply_cartesian_command& law, const JointState& state,
                            const JointVector& candidate) noexcept;
  /// The nullspace target, from `law`'s to `candidate`, at `law`'s nullspace stiffness: the
  /// springs' potential change at the measured joints, 1/2 sum k_i ((q_i - q'_ns,i)^2 -
  /// (q_i - q_ns,i)^2), from the nullspace account. An upper bound of what the projected spring
  /// injects (the projection only takes away).
  double payNullspaceMove(const comply_cartesian_command& law, const JointState& state,
                          const JointVector& candidate) noexcept;
  /// The joint stiffness under joint control, to `candidate`, from the task account.
  double payJointChange(const comply_joint_command& law, const JointState& state,
                        const JointVector& candidate) noexcept;

  /// One cycle of the refill under the gains in force `gains`. `torque_clipped`: the last torque
  /// was rate or effort limited, so the law's damping did not all reach the arm.
  void refillCartesian(const comply_cartesian_command& gains, const model::Data& data,
                       double period_s, bool torque_clipped) noexcept;
  void refillJoint(const comply_joint_command& gains, const JointState& state, double period_s,
                   bool torque_clipped) noexcept;

  [[nodiscard]] const EnergyAccount& task() const noexcept { return task_; }
  [[nodiscard]] const EnergyAccount& nullspace() const noexcept { return nullspace_; }
  /// [J] paid for increases since activation.
  [[nodiscard]] double injected() const noexcept { return injected_j_; }
  /// [J] credited by the refill since activation.
  [[nodiscard]] double dissipated() const noexcept { return dissipated_j_; }
  /// [J] this cycle's changes not paid for, both accounts.
  [[nodiscard]] double refused() const noexcept { return refused_j_; }

 private:
  using JacobianTranspose = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, kMaxDof, 6>;

  /// Pays what `account` can of a change that injects `injected_j` (of `full_j` the whole
  /// change would have), or takes back what a decrease released.
  void settle(EnergyAccount& account, double full_j, double injected_j) noexcept;
  /// A change of diagonal springs (`count` of them, at rest at `rest`, now at `position`) from
  /// `stiffness` to `candidate`, paid from `account`.
  double payDiagonal(EnergyAccount& account, const double* stiffness, const double* candidate,
                     const double* rest, const double* position, int count) noexcept;
  void openWindow(bool ratio) noexcept;
  /// Ratio mode: from the window's smallest stiffness bounds (in: translational, rotational
  /// [N/m, N m/rad]) a lower bound of the law's damping (out: [N s/m, N m s/rad]).
  bool ratioDampingBound(const model::Data& data, double& translational,
                         double& rotational) noexcept;

  double task_initial_j_;
  double nullspace_initial_j_;
  EnergyAccount task_;
  EnergyAccount nullspace_;
  double injected_j_ = 0.0;
  double dissipated_j_ = 0.0;
  double refused_j_ = 0.0;  ///< this cycle's, not a total: a held-back change is offered again

  /// Gershgorin bounds of the gains in force (Cartesian): the smallest damping (ratio mode: the
  /// smallest stiffness) and the largest stiffness per block, and the smallest damping ratio.
  struct Bounds {
    double translational = 0.0;  ///< [N s/m]; ratio mode [N/m]
    double rotational = 0.0;     ///< [N m s/rad]; ratio mode [N m/rad]
    double ratio = 0.0;
    double stiffest_translational = 0.0;  ///< [N/m]
    double stiffest_rotational = 0.0;     ///< [N m/rad]
  } bounds_;

  // Refill window: the error increments (position minus commanded velocity times time) summed
  // since it opened, and the smallest damping (ratio mode: stiffness and ratio) seen in it.
  static constexpr double kWindowS = 0.01;
  bool window_open_ = false;
  bool window_ratio_ = false;
  bool window_clipped_ = false;  ///< shaping clipped a torque in the window: it credits nothing
  double window_elapsed_s_ = 0.0;
  Vector6d window_increment_ = Vector6d::Zero();
  double window_translational_ = 0.0;
  double window_rotational_ = 0.0;
  double window_ratio_min_ = 0.0;
  double window_stiffest_translational_ = 0.0;  ///< largest stiffness seen: the sampling's share
  double window_stiffest_rotational_ = 0.0;
  JointVector joint_window_increment_;
  JointVector window_joint_damping_;
  JointVector window_joint_stiffest_;
  Eigen::Vector3d previous_position_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond previous_orientation_ = Eigen::Quaterniond::Identity();
  JointVector previous_joints_;
  Eigen::LLT<JointMatrix> mass_factor_;
};

}  // namespace comply::pipeline
