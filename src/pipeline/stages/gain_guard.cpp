#include "comply/pipeline/gain_guard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;

/// Moves `count` entries of `current` toward `target` along the straight line, so that no entry
/// moves more than `max_step`: a matrix stays a convex combination of two PSD matrices.
/// Returns whether `current` has arrived.
bool approach(double* current, const double* target, int count, double max_step) noexcept {
  double largest = 0.0;
  for (int i = 0; i < count; ++i) {
    largest = std::max(largest, std::abs(target[i] - current[i]));
  }
  const double fraction = largest <= max_step ? 1.0 : max_step / largest;
  for (int i = 0; i < count; ++i) {
    current[i] = fraction == 1.0 ? target[i] : current[i] + fraction * (target[i] - current[i]);
  }
  return fraction == 1.0;
}

/// Diagonal gains: each entry on its own, at most `max_step` (they stay non-negative).
bool approachEach(double* current, const double* target, int count, double max_step) noexcept {
  bool arrived = true;
  for (int i = 0; i < count; ++i) {
    const double change = target[i] - current[i];
    const bool within = std::abs(change) <= max_step;
    current[i] = within ? target[i] : current[i] + std::copysign(max_step, change);
    arrived = arrived && within;
  }
  return arrived;
}

void copy(double* to, const double* from, int count) noexcept {
  std::copy_n(from, count, to);
}

// The variant's alternative is fixed for the controller's life, so std::get_if is never null
// here; it is used instead of std::get, which could throw, in functions that must not.

/// `current` moved the fraction `beta` of the way to `target`; all of it lands on `target` exactly.
void blend(double* current, const double* target, int count, double beta) noexcept {
  for (int i = 0; i < count; ++i) {
    current[i] = beta == 1.0 ? target[i] : current[i] + beta * (target[i] - current[i]);
  }
}

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

/// The task frame of a bus, normalised; an all-zero quaternion is the identity, as the laws
/// read it.
Eigen::Quaterniond frameOf(const double* xyzw) noexcept {
  const Eigen::Quaterniond frame = schema::fromXyzw(xyzw);
  const double norm = frame.norm();
  return norm > 1e-12 ? Eigen::Quaterniond(frame.coeffs() / norm) : Eigen::Quaterniond::Identity();
}

/// 1/2 e^T R K R^T e for a row-major task-frame K: the spring energy at error `error` [J].
double springEnergy(const double* stiffness, const Eigen::Quaterniond& frame,
                    const Eigen::Vector3d& error) noexcept {
  const Eigen::Vector3d in_task = frame.conjugate() * error;
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> k(stiffness);
  return 0.5 * in_task.dot(k * in_task);
}

/// The task-space gains a Cartesian change moves: both stiffness blocks and the frame.
struct TaskStiffness {
  double translational[9];
  double rotational[9];
  Eigen::Quaterniond frame;

  [[nodiscard]] double energy(const Eigen::Vector3d& position_error,
                              const Eigen::Vector3d& orientation_error) const noexcept {
    return springEnergy(translational, frame, position_error) +
           springEnergy(rotational, frame, orientation_error);
  }
  /// The gains a fraction `beta` of the way from `from` to `to`.
  static TaskStiffness between(const TaskStiffness& from, const TaskStiffness& to,
                               double beta) noexcept {
    TaskStiffness result;
    for (int i = 0; i < 9; ++i) {
      result.translational[i] =
          from.translational[i] + beta * (to.translational[i] - from.translational[i]);
      result.rotational[i] = from.rotational[i] + beta * (to.rotational[i] - from.rotational[i]);
    }
    result.frame = from.frame.slerp(beta, to.frame);
    return result;
  }
};

TaskStiffness taskStiffnessOf(const Cartesian& bus) noexcept {
  TaskStiffness result;
  copy(result.translational, bus.stiffness_translational, 9);
  copy(result.rotational, bus.stiffness_rotational, 9);
  result.frame = frameOf(bus.task_frame);
  return result;
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

GainGuard::GainGuard(const GainRampConfig& ramps, const PassivityConfig& passivity)
    : ramps_(ramps), passivity_(passivity) {
  task_.max_j = passivity.tank_max_j;
  task_.min_j = passivity.tank_min_j;
  nullspace_.max_j = passivity.nullspace_tank_max_j;
  nullspace_.min_j = std::min(passivity.tank_min_j, passivity.nullspace_tank_initial_j);
}

model::Quantity GainGuard::quantities(bool cartesian) const noexcept {
  return passivity_.enabled && cartesian ? model::Quantity::kPose : model::Quantity::kNone;
}

void GainGuard::reset(const CommandBus& command, const model::Data& data, const JointState& state,
                      Diagnostics& diagnostics) noexcept {
  law_ = command;
  task_.energy_j = passivity_.tank_initial_j;
  task_.outstanding_j = 0.0;
  nullspace_.energy_j = passivity_.nullspace_tank_initial_j;
  nullspace_.outstanding_j = 0.0;
  injected_j_ = dissipated_j_ = refused_j_ = 0.0;
  pending_ = false;
  cacheBounds();
  fraction_ = 1.0;
  target_stiffness_ = stiffnessOf(command);
  from_distance_ = 0.0;
  if (const auto* cartesian = std::get_if<Cartesian>(&command)) {
    target_frame_ = frameOf(cartesian->task_frame);
  }
  from_angle_ = 0.0;
  window_increment_.setZero();
  joint_window_increment_.setZero(state.position.size());
  window_elapsed_s_ = 0.0;
  window_open_ = false;
  previous_position_ = data.tip_position;
  previous_orientation_ = data.tip_orientation;
  previous_joints_ = state.position;
  publish(diagnostics);
}

GainGuard::StiffnessStack GainGuard::stiffnessOf(const CommandBus& bus) noexcept {
  StiffnessStack stack;
  if (const auto* cartesian = std::get_if<Cartesian>(&bus)) {
    const int dof = cartesian->dof;
    stack.resize(18 + dof);
    copy(stack.data(), cartesian->stiffness_translational, 9);
    copy(stack.data() + 9, cartesian->stiffness_rotational, 9);
    copy(stack.data() + 18, cartesian->nullspace_stiffness, dof);
  } else {
    const auto& joint = *std::get_if<Joint>(&bus);
    stack.resize(joint.dof);
    copy(stack.data(), joint.stiffness, joint.dof);
  }
  return stack;
}

void GainGuard::takeCommand(const CommandBus& command) noexcept {
  // Motion, feedforward and stamp pass at once; the gains in force stay until update() moves them.
  pending_ = true;
  std::visit(
      [this](const auto& incoming) noexcept {
        using Bus = std::decay_t<decltype(incoming)>;
        auto& law = *std::get_if<Bus>(&law_);
        const Bus in_force = law;
        law = incoming;
        if constexpr (std::is_same_v<Bus, Cartesian>) {
          copy(law.stiffness_translational, in_force.stiffness_translational, 9);
          copy(law.stiffness_rotational, in_force.stiffness_rotational, 9);
          copy(law.damping_translational, in_force.damping_translational, 9);
          copy(law.damping_rotational, in_force.damping_rotational, 9);
          copy(law.damping_ratio, in_force.damping_ratio, 6);
          law.damping_mode = in_force.damping_mode;
          copy(law.task_frame, in_force.task_frame, 4);
          copy(law.nullspace_stiffness, in_force.nullspace_stiffness, COMPLY_MAX_DOF);
          copy(law.nullspace_damping, in_force.nullspace_damping, COMPLY_MAX_DOF);
        } else {
          copy(law.stiffness, in_force.stiffness, COMPLY_MAX_DOF);
          copy(law.damping, in_force.damping, COMPLY_MAX_DOF);
        }
      },
      command);
  // A new stiffness target restarts the fraction; a motion-only command does not.
  const StiffnessStack target = stiffnessOf(command);
  if (target != target_stiffness_) {
    target_stiffness_ = target;
    from_distance_ = (stiffnessOf(law_) - target).norm();
  }
  if (const auto* cartesian = std::get_if<Cartesian>(&command)) {
    const Eigen::Quaterniond frame = frameOf(cartesian->task_frame);
    if (frame.coeffs() != target_frame_.coeffs()) {
      target_frame_ = frame;
      from_angle_ = frameOf(std::get_if<Cartesian>(&law_)->task_frame).angularDistance(frame);
    }
  }
}

void GainGuard::update(const CommandBus& command, const model::Data& data, const JointState& state,
                       double period_s, bool torque_clipped, Diagnostics& diagnostics) noexcept {
  refused_j_ = 0.0;
  // Once the gains in force are the command's, nothing moves them until the next command: the
  // common cycle then only keeps the refill window.
  const auto* cartesian = std::get_if<Cartesian>(&command);
  if (pending_) {
    pending_ = cartesian != nullptr ? !updateCartesian(*cartesian, data, state, period_s)
                                    : !updateJoint(*std::get_if<Joint>(&command), state, period_s);
    cacheBounds();
    fraction_ = gainFraction();
  }
  if (passivity_.enabled) {
    if (cartesian != nullptr) {
      refillCartesian(*std::get_if<Cartesian>(&law_), data, period_s, torque_clipped);
    } else {
      refillJoint(*std::get_if<Joint>(&law_), state, period_s, torque_clipped);
    }
  }
  publish(diagnostics);
}

void GainGuard::cacheBounds() noexcept {
  const auto* law = std::get_if<Cartesian>(&law_);
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

bool GainGuard::updateCartesian(const Cartesian& target, const model::Data& data,
                                const JointState& state, double period_s) noexcept {
  auto& law = *std::get_if<Cartesian>(&law_);
  const bool ramp = ramps_.enabled;
  const int dof = target.dof;
  bool arrived = true;

  // Damping injects nothing: ramped, never charged. A change of mode has nothing to ramp between.
  if (law.damping_mode != target.damping_mode || !ramp) {
    law.damping_mode = target.damping_mode;
    copy(law.damping_translational, target.damping_translational, 9);
    copy(law.damping_rotational, target.damping_rotational, 9);
    copy(law.damping_ratio, target.damping_ratio, 6);
    copy(law.nullspace_damping, target.nullspace_damping, dof);
  } else {
    arrived &= approach(law.damping_translational, target.damping_translational, 9,
                        ramps_.translational_damping_per_s * period_s);
    arrived &= approach(law.damping_rotational, target.damping_rotational, 9,
                        ramps_.rotational_damping_per_s * period_s);
    arrived &=
        approach(law.damping_ratio, target.damping_ratio, 6, ramps_.damping_ratio_per_s * period_s);
    arrived &= approachEach(law.nullspace_damping, target.nullspace_damping, dof,
                            ramps_.joint_damping_per_s * period_s);
  }

  // The stiffness and frame this cycle would move to.
  const TaskStiffness in_force = taskStiffnessOf(law);
  TaskStiffness candidate = taskStiffnessOf(target);
  JointVector nullspace_candidate(dof);
  copy(nullspace_candidate.data(), target.nullspace_stiffness, dof);
  if (ramp) {
    candidate = in_force;
    arrived &= approach(candidate.translational, target.stiffness_translational, 9,
                        ramps_.translational_stiffness_per_s * period_s);
    arrived &= approach(candidate.rotational, target.stiffness_rotational, 9,
                        ramps_.rotational_stiffness_per_s * period_s);
    const Eigen::Quaterniond goal = frameOf(target.task_frame);
    const double angle = in_force.frame.angularDistance(goal);
    const double step = ramps_.task_frame_rad_per_s * period_s;
    candidate.frame = angle <= step ? goal : in_force.frame.slerp(step / angle, goal);
    arrived &= angle <= step;
    copy(nullspace_candidate.data(), law.nullspace_stiffness, dof);
    arrived &= approachEach(nullspace_candidate.data(), target.nullspace_stiffness, dof,
                            ramps_.joint_stiffness_per_s * period_s);
  }

  double beta = 1.0;
  double nullspace_beta = 1.0;
  if (passivity_.enabled) {
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
    beta = payableFraction(full, task_.spendable(), injection);
    const double injected = beta == 1.0 ? full : injection(beta);
    settle(task_, full, injected);

    double nullspace_full = 0.0;
    for (int i = 0; i < dof; ++i) {
      const double error = law.nullspace_position[i] - state.position[i];
      nullspace_full += 0.5 * (nullspace_candidate[i] - law.nullspace_stiffness[i]) * error * error;
    }
    nullspace_beta = payableFraction(nullspace_full, nullspace_.spendable(),
                                     [nullspace_full](double f) { return f * nullspace_full; });
    settle(nullspace_, nullspace_full, nullspace_beta * nullspace_full);
  }

  const TaskStiffness applied =
      beta == 1.0 ? candidate : TaskStiffness::between(in_force, candidate, beta);
  copy(law.stiffness_translational, applied.translational, 9);
  copy(law.stiffness_rotational, applied.rotational, 9);
  // The command's own numbers once the frame has arrived, so a guard with nothing to hold back
  // hands the law the command bit for bit.
  if (beta == 1.0 && candidate.frame.coeffs() == frameOf(target.task_frame).coeffs()) {
    copy(law.task_frame, target.task_frame, 4);
  } else if (applied.frame.coeffs() != in_force.frame.coeffs()) {
    schema::toXyzw(applied.frame, law.task_frame);
  }
  blend(law.nullspace_stiffness, nullspace_candidate.data(), dof, nullspace_beta);
  return arrived && beta == 1.0 && nullspace_beta == 1.0;
}

bool GainGuard::updateJoint(const Joint& target, const JointState& state,
                            double period_s) noexcept {
  auto& law = *std::get_if<Joint>(&law_);
  const int dof = target.dof;
  JointVector candidate(dof);
  bool arrived = true;
  if (ramps_.enabled) {
    arrived &=
        approachEach(law.damping, target.damping, dof, ramps_.joint_damping_per_s * period_s);
    copy(candidate.data(), law.stiffness, dof);
    arrived &= approachEach(candidate.data(), target.stiffness, dof,
                            ramps_.joint_stiffness_per_s * period_s);
  } else {
    copy(law.damping, target.damping, dof);
    copy(candidate.data(), target.stiffness, dof);
  }
  double beta = 1.0;
  if (passivity_.enabled) {
    double full = 0.0;
    for (int i = 0; i < dof; ++i) {
      const double error = law.position[i] - state.position[i];
      full += 0.5 * (candidate[i] - law.stiffness[i]) * error * error;
    }
    beta = payableFraction(full, task_.spendable(), [full](double f) { return f * full; });
    settle(task_, full, beta * full);
  }
  blend(law.stiffness, candidate.data(), dof, beta);
  return arrived && beta == 1.0;
}

void GainGuard::settle(EnergyAccount& account, double full_j, double injected_j) noexcept {
  if (injected_j > 0.0) {
    injected_j_ += account.pay(injected_j);
  } else if (injected_j < 0.0) {
    account.takeBack(-injected_j);
  }
  refused_j_ += std::max(full_j - std::max(injected_j, 0.0), 0.0);  // both accounts, this cycle
}

void GainGuard::openWindow(bool ratio) noexcept {
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

void GainGuard::refillCartesian(const Cartesian& gains, const model::Data& data, double period_s,
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

bool GainGuard::ratioDampingBound(const model::Data& data, double& translational,
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

void GainGuard::refillJoint(const Joint& gains, const JointState& state, double period_s,
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

double GainGuard::gainFraction() const noexcept {
  double fraction = 1.0;
  if (from_distance_ > 0.0) {
    const double remaining = (stiffnessOf(law_) - target_stiffness_).norm();
    fraction = std::clamp(1.0 - remaining / from_distance_, 0.0, 1.0);
  }
  if (const auto* cartesian = std::get_if<Cartesian>(&law_);
      cartesian != nullptr && from_angle_ > 0.0) {
    const double remaining = frameOf(cartesian->task_frame).angularDistance(target_frame_);
    fraction = std::min(fraction, std::clamp(1.0 - remaining / from_angle_, 0.0, 1.0));
  }
  return fraction;
}

void GainGuard::publish(Diagnostics& diagnostics) const noexcept {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  diagnostics.passivity_enabled.store(passivity_.enabled, kRelaxed);
  diagnostics.tank_energy_j.store(passivity_.enabled ? task_.energy_j : 0.0, kRelaxed);
  diagnostics.nullspace_tank_energy_j.store(passivity_.enabled ? nullspace_.energy_j : 0.0,
                                            kRelaxed);
  diagnostics.injected_j.store(injected_j_, kRelaxed);
  diagnostics.dissipated_j.store(dissipated_j_, kRelaxed);
  diagnostics.refused_j.store(refused_j_, kRelaxed);
  diagnostics.gain_fraction.store(fraction_, kRelaxed);
}

}  // namespace comply::pipeline
