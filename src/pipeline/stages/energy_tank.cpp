#include "comply/pipeline/energy_tank.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "comply/core/rotation.hpp"
#include "comply/pipeline/task_stiffness.hpp"

namespace comply::pipeline {
namespace {

using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;

/// An upper bound of the largest eigenvalue of a symmetric 3x3 (row-major; Gershgorin).
double largestEigenvalueBound(const double* m) noexcept {
  double bound = 0.0;
  for (int row = 0; row < 3; ++row) {
    double sum = 0.0;
    for (int col = 0; col < 3; ++col) {
      sum += std::abs(m[row * 3 + col]);
    }
    bound = std::max(bound, sum);
  }
  return bound;
}

/// A lower bound of the smallest eigenvalue of a symmetric 3x3 (row-major), >= 0 (Gershgorin;
/// exact for the diagonal matrices commands usually carry).
double smallestEigenvalueBound(const double* m) noexcept {
  double bound = m[0];
  for (int row = 0; row < 3; ++row) {
    double off = 0.0;
    for (int col = 0; col < 3; ++col) {
      off += col == row ? 0.0 : std::abs(m[row * 3 + col]);
    }
    bound = std::min(bound, m[row * 3 + row] - off);
  }
  return std::max(bound, 0.0);
}

/// The largest fraction (0..1) of a change from `from` to `to` whose injected energy the account
/// can pay; the energy function is linear in the stiffness and smooth in the frame's angle, so a
/// few secant steps settle it, and 0 is always payable.
template <typename EnergyAt>
double payableFraction(double injection_j, double available_j, EnergyAt energy_at) noexcept {
  if (injection_j <= available_j) {
    return 1.0;
  }
  if (available_j <= 0.0) {
    return 0.0;
  }
  double beta = available_j / injection_j;
  for (int iteration = 0; iteration < 3; ++iteration) {
    const double injected = energy_at(beta);
    if (injected <= available_j) {
      return beta;
    }
    beta *= available_j / injected;
  }
  return energy_at(beta) <= available_j ? beta : 0.0;
}

}  // namespace

double EnergyAccount::pay(double injection_j) noexcept {
  const double paid = std::clamp(injection_j, 0.0, std::max(spendable(), 0.0));
  energy_j -= paid;
  outstanding_j += paid;
  return paid;
}

void EnergyAccount::takeBack(double released_j) noexcept {
  const double credit = std::min(released_j, outstanding_j);
  outstanding_j -= credit;
  energy_j = std::min(energy_j + credit, max_j);
}

double EnergyAccount::refill(double credit_j) noexcept {
  const double taken = std::clamp(max_j - energy_j, 0.0, credit_j);
  energy_j += taken;
  return taken;
}

EnergyTank::EnergyTank(const PassivityConfig& passivity) noexcept
    : task_initial_j_(passivity.tank_initial_j),
      nullspace_initial_j_(passivity.nullspace_tank_initial_j) {
  task_.max_j = passivity.tank_max_j;
  task_.min_j = passivity.tank_min_j;
  nullspace_.max_j = passivity.nullspace_tank_max_j;
  nullspace_.min_j = std::min(passivity.tank_min_j, passivity.nullspace_tank_initial_j);
}

void EnergyTank::reset(const model::Data& data, const JointState& state) noexcept {
  task_.energy_j = task_initial_j_;
  task_.outstanding_j = 0.0;
  nullspace_.energy_j = nullspace_initial_j_;
  nullspace_.outstanding_j = 0.0;
  injected_j_ = dissipated_j_ = refused_j_ = 0.0;
  window_increment_.setZero();
  joint_window_increment_.setZero(state.position.size());
  window_elapsed_s_ = 0.0;
  window_open_ = false;
  previous_position_ = data.tip_position;
  previous_orientation_ = data.tip_orientation;
  previous_joints_ = state.position;
}

void EnergyTank::cacheBounds(const CommandBus& law_bus) noexcept {
  const auto* law = std::get_if<Cartesian>(&law_bus);
  if (law == nullptr) {
    return;
  }
  const bool ratio = law->damping_mode == COMPLY_DAMPING_RATIO;
  // Ratio mode bounds the damping from the smallest stiffness; else the damping blocks bound it.
  bounds_.translational =
      smallestEigenvalueBound(ratio ? law->stiffness_translational : law->damping_translational);
  bounds_.rotational =
      smallestEigenvalueBound(ratio ? law->stiffness_rotational : law->damping_rotational);
  bounds_.ratio = *std::min_element(law->damping_ratio, law->damping_ratio + 6);
  bounds_.stiffest_translational = largestEigenvalueBound(law->stiffness_translational);
  bounds_.stiffest_rotational = largestEigenvalueBound(law->stiffness_rotational);
}

double EnergyTank::payTaskChange(const Cartesian& law, const model::Data& data,
                                 const TaskStiffness& in_force,
                                 const TaskStiffness& candidate) noexcept {
  const Eigen::Vector3d position_error =
      data.tip_position - Eigen::Vector3d(law.position[0], law.position[1], law.position[2]);
  const Eigen::Vector3d orientation_error =
      orientationError(data.tip_orientation, frameOf(law.orientation));
  const double before = in_force.energy(position_error, orientation_error);
  const auto injection = [&](double fraction) noexcept {
    return TaskStiffness::between(in_force, candidate, fraction)
               .energy(position_error, orientation_error) -
           before;
  };
  const double full = injection(1.0);
  const double beta = payableFraction(full, task_.spendable(), injection);
  const double injected = beta == 1.0 ? full : injection(beta);
  settle(task_, full, injected);
  return beta;
}

double EnergyTank::payNullspaceChange(const Cartesian& law, const JointState& state,
                                      const JointVector& candidate) noexcept {
  return payDiagonal(nullspace_, law.nullspace_stiffness, candidate.data(), law.nullspace_position,
                     state.position.data(), static_cast<int>(candidate.size()));
}

double EnergyTank::payNullspaceMove(const Cartesian& law, const JointState& state,
                                    const JointVector& candidate) noexcept {
  const auto count = candidate.size();
  const auto injection = [&](double fraction) noexcept {
    double energy = 0.0;
    for (Eigen::Index i = 0; i < count; ++i) {
      const double from = law.nullspace_position[i] - state.position[i];
      const double to = from + fraction * (candidate[i] - law.nullspace_position[i]);
      energy += 0.5 * law.nullspace_stiffness[i] * (to * to - from * from);
    }
    return energy;
  };
  // Convex in the fraction and 0 at 0: the secant's first step is already payable.
  const double full = injection(1.0);
  const double beta = payableFraction(full, nullspace_.spendable(), injection);
  const double injected = beta == 1.0 ? full : injection(beta);
  settle(nullspace_, full, injected);
  return beta;
}

double EnergyTank::payJointChange(const Joint& law, const JointState& state,
                                  const JointVector& candidate) noexcept {
  return payDiagonal(task_, law.stiffness, candidate.data(), law.position, state.position.data(),
                     static_cast<int>(candidate.size()));
}

double EnergyTank::payDiagonal(EnergyAccount& account, const double* stiffness,
                               const double* candidate, const double* rest, const double* position,
                               int count) noexcept {
  double full = 0.0;
  for (int i = 0; i < count; ++i) {
    const double error = rest[i] - position[i];
    full += 0.5 * (candidate[i] - stiffness[i]) * error * error;
  }
  const double beta =
      payableFraction(full, account.spendable(), [full](double f) { return f * full; });
  settle(account, full, beta * full);
  return beta;
}

void EnergyTank::settle(EnergyAccount& account, double full_j, double injected_j) noexcept {
  if (injected_j > 0.0) {
    injected_j_ += account.pay(injected_j);
  } else if (injected_j < 0.0) {
    account.takeBack(-injected_j);
  }
  refused_j_ += std::max(full_j - std::max(injected_j, 0.0), 0.0);  // both accounts, this cycle
}

void EnergyTank::openWindow(bool ratio) noexcept {
  window_open_ = true;
  window_ratio_ = ratio;
  window_clipped_ = false;
  window_elapsed_s_ = 0.0;
  window_increment_.setZero();
  joint_window_increment_.setZero();
  constexpr double kNone = std::numeric_limits<double>::infinity();
  window_translational_ = window_rotational_ = window_ratio_min_ = kNone;
  window_stiffest_translational_ = window_stiffest_rotational_ = 0.0;
  window_joint_damping_.setConstant(joint_window_increment_.size(), kNone);
  window_joint_stiffest_.setZero(joint_window_increment_.size());
}

void EnergyTank::refillCartesian(const Cartesian& gains, const model::Data& data, double period_s,
                                 bool torque_clipped) noexcept {
  // This cycle's error increment: how far the tool moved relative to the commanded twist. The
  // turn since the last cycle as 2 vec(q q_prev^-1) (w >= 0): 2 sin(angle / 2) <= angle, so the
  // bound stays a lower one, without a logarithm every cycle.
  Eigen::Quaterniond turn = data.tip_orientation * previous_orientation_.conjugate();
  if (turn.w() < 0.0) {
    turn.coeffs() = -turn.coeffs();
  }
  Vector6d increment;
  increment.head<3>() = data.tip_position - previous_position_ -
                        period_s * Eigen::Vector3d(gains.twist[0], gains.twist[1], gains.twist[2]);
  increment.tail<3>() =
      2.0 * turn.vec() - period_s * Eigen::Vector3d(gains.twist[3], gains.twist[4], gains.twist[5]);
  previous_position_ = data.tip_position;
  previous_orientation_ = data.tip_orientation;
  if (task_.energy_j >= task_.max_j) {
    window_open_ = false;  // full: nothing to credit; a window opens when it is not
    return;
  }

  const bool ratio = gains.damping_mode == COMPLY_DAMPING_RATIO;
  if (!window_open_ || ratio != window_ratio_) {
    openWindow(ratio);
  }
  window_increment_ += increment;
  window_elapsed_s_ += period_s;
  window_clipped_ = window_clipped_ || torque_clipped;
  // The smallest damping (ratio mode: stiffness and ratio) and the largest stiffness of the window.
  window_translational_ = std::min(window_translational_, bounds_.translational);
  window_rotational_ = std::min(window_rotational_, bounds_.rotational);
  window_ratio_min_ = std::min(window_ratio_min_, bounds_.ratio);
  window_stiffest_translational_ =
      std::max(window_stiffest_translational_, bounds_.stiffest_translational);
  window_stiffest_rotational_ = std::max(window_stiffest_rotational_, bounds_.stiffest_rotational);
  if (window_elapsed_s_ < kWindowS) {
    return;
  }
  window_open_ = false;
  // A torque the shaping clipped is not the law's: its damping did not all act on the arm, and a
  // rate limit's lag is itself active. Such a window credits nothing.
  if (window_clipped_) {
    return;
  }
  double damping_translational = window_translational_;
  double damping_rotational = window_rotational_;
  if (ratio && !ratioDampingBound(data, damping_translational, damping_rotational)) {
    return;
  }
  // A spring sampled with a zero-order hold acts with a delay of half a period, like a negative
  // damping of K T / 2 (Colgate and Schenkel's condition for a passive virtual wall,
  // b > K T / 2): only the damping beyond that dissipates.
  const double delay_share = 0.5 * period_s;
  damping_translational -= delay_share * window_stiffest_translational_;
  damping_rotational -= delay_share * window_stiffest_rotational_;
  const double credit =
      (std::max(damping_translational, 0.0) * window_increment_.head<3>().squaredNorm() +
       std::max(damping_rotational, 0.0) * window_increment_.tail<3>().squaredNorm()) /
      window_elapsed_s_;
  dissipated_j_ += task_.refill(credit);
}

bool EnergyTank::ratioDampingBound(const model::Data& data, double& translational,
                                   double& rotational) noexcept {
  // In: the window's smallest stiffness bounds k_t, k_r. Out: d_t, d_r with
  // D >= diag(d_t I, d_r I). With P = diag(I, s I), s^2 = k_r / k_t: K >= k_t P^2 and
  // Lambda >= mu P^2 for mu = 1 / lambda_max(P Lambda^-1 P), so Lambda # K >= sqrt(mu k_t) P^2
  // and D = 2 S (Lambda # K) S >= 2 zeta_min sqrt(mu k_t) P^2.
  const double stiffness_translational = translational;
  const double stiffness_rotational = rotational;
  const model::Quantity needed = model::Quantity::kMassMatrix | model::Quantity::kJacobian;
  if (!(stiffness_translational > 0.0 && stiffness_rotational > 0.0 && window_ratio_min_ > 0.0) ||
      !model::contains(data.computed, needed)) {
    return false;
  }
  mass_factor_.compute(data.mass_matrix);
  if (mass_factor_.info() != Eigen::Success) {
    return false;
  }
  JacobianTranspose solved = data.jacobian.transpose();
  mass_factor_.matrixL().solveInPlace(solved);
  Eigen::Matrix<double, 6, 6> inverse_inertia;
  inverse_inertia.noalias() = solved.transpose() * solved;
  const double scale = std::sqrt(stiffness_rotational / stiffness_translational);
  double largest_row_sum = 0.0;  // Gershgorin: an upper bound of lambda_max
  for (int row = 0; row < 6; ++row) {
    double sum = 0.0;
    for (int col = 0; col < 6; ++col) {
      const double weight = (row < 3 ? 1.0 : scale) * (col < 3 ? 1.0 : scale);
      sum += weight * std::abs(inverse_inertia(row, col));
    }
    largest_row_sum = std::max(largest_row_sum, sum);
  }
  if (!(largest_row_sum > 0.0)) {
    return false;
  }
  translational = 2.0 * window_ratio_min_ * std::sqrt(stiffness_translational / largest_row_sum);
  rotational = translational * scale * scale;
  return true;
}

void EnergyTank::refillJoint(const Joint& gains, const JointState& state, double period_s,
                             bool torque_clipped) noexcept {
  const int dof = gains.dof;
  if (task_.energy_j >= task_.max_j) {
    window_open_ = false;  // as in refillCartesian()
    previous_joints_ = state.position;
    return;
  }
  if (!window_open_) {
    openWindow(false);
  }
  for (int i = 0; i < dof; ++i) {
    joint_window_increment_[i] +=
        state.position[i] - previous_joints_[i] - period_s * gains.velocity[i];
    window_joint_damping_[i] = std::min(window_joint_damping_[i], std::max(gains.damping[i], 0.0));
    window_joint_stiffest_[i] = std::max(window_joint_stiffest_[i], gains.stiffness[i]);
  }
  previous_joints_ = state.position;
  window_elapsed_s_ += period_s;
  window_clipped_ = window_clipped_ || torque_clipped;
  if (window_elapsed_s_ < kWindowS) {
    return;
  }
  window_open_ = false;
  if (window_clipped_) {
    return;  // as in refillCartesian()
  }
  double credit = 0.0;
  for (int i = 0; i < dof; ++i) {
    // Net of the sampled spring's own activity, as in refillCartesian().
    const double damping = window_joint_damping_[i] - 0.5 * period_s * window_joint_stiffest_[i];
    credit += std::max(damping, 0.0) * joint_window_increment_[i] * joint_window_increment_[i];
  }
  dissipated_j_ += task_.refill(credit / window_elapsed_s_);
}

}  // namespace comply::pipeline
