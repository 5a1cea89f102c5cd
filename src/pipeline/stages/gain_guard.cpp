#include "comply/pipeline/gain_guard.hpp"

#include <algorithm>
#include <type_traits>

#include "comply/pipeline/gain_ramps.hpp"
#include "comply/pipeline/task_stiffness.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;

void copy(double* to, const double* from, int count) noexcept {
  std::copy_n(from, count, to);
}

// The variant's alternative is fixed for the controller's life, so std::get_if is never null
// here; it is used instead of std::get, which could throw, in functions that must not.

// The steps of GainGuard::updateCartesian(), in order; one that moves gains returns whether they
// have arrived.

/// Damping injects nothing: ramped, never charged. A change of mode has nothing to ramp between.
bool approachDampings(Cartesian& law, const Cartesian& target, const GainRampConfig& ramps,
                      double period_s) noexcept {
  const int dof = target.dof;
  bool arrived = true;
  if (law.damping_mode != target.damping_mode || !ramps.enabled) {
    law.damping_mode = target.damping_mode;
    copy(law.damping_translational, target.damping_translational, 9);
    copy(law.damping_rotational, target.damping_rotational, 9);
    copy(law.damping_ratio, target.damping_ratio, 6);
    copy(law.nullspace_damping, target.nullspace_damping, dof);
  } else {
    arrived &= approach(law.damping_translational, target.damping_translational, 9,
                        ramps.translational_damping_per_s * period_s);
    arrived &= approach(law.damping_rotational, target.damping_rotational, 9,
                        ramps.rotational_damping_per_s * period_s);
    arrived &=
        approach(law.damping_ratio, target.damping_ratio, 6, ramps.damping_ratio_per_s * period_s);
    arrived &= approachEach(law.nullspace_damping, target.nullspace_damping, dof,
                            ramps.joint_damping_per_s * period_s);
  }
  return arrived;
}

/// The stiffness, frame (`candidate`) and nullspace stiffness this cycle would move to from the
/// gains in force (`law`, its task part `in_force`): the target's, or the ramps' step toward it.
bool stiffnessCandidate(const Cartesian& law, const TaskStiffness& in_force,
                        const Cartesian& target, const GainRampConfig& ramps, double period_s,
                        TaskStiffness& candidate, JointVector& nullspace_candidate) noexcept {
  const int dof = target.dof;
  if (!ramps.enabled) {
    candidate = TaskStiffness::of(target);
    copy(nullspace_candidate.data(), target.nullspace_stiffness, dof);
    return true;
  }
  bool arrived = true;
  candidate = in_force;
  arrived &= approach(candidate.translational, target.stiffness_translational, 9,
                      ramps.translational_stiffness_per_s * period_s);
  arrived &= approach(candidate.rotational, target.stiffness_rotational, 9,
                      ramps.rotational_stiffness_per_s * period_s);
  arrived &= approachFrame(candidate.frame, frameOf(target.task_frame),
                           ramps.task_frame_rad_per_s * period_s);
  copy(nullspace_candidate.data(), law.nullspace_stiffness, dof);
  arrived &= approachEach(nullspace_candidate.data(), target.nullspace_stiffness, dof,
                          ramps.joint_stiffness_per_s * period_s);
  return arrived;
}

/// Moves the gains in force the fraction `beta` (task) and `nullspace_beta` of the way to the
/// candidates the tank paid for.
void applyStiffness(Cartesian& law, const Cartesian& target, const TaskStiffness& in_force,
                    const TaskStiffness& candidate, double beta,
                    const JointVector& nullspace_candidate, double nullspace_beta) noexcept {
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
  blend(law.nullspace_stiffness, nullspace_candidate.data(), target.dof, nullspace_beta);
}

}  // namespace

GainGuard::GainGuard(const GainRampConfig& ramps, const PassivityConfig& passivity)
    : ramps_(ramps), passivity_(passivity), tank_(passivity) {}

model::Quantity GainGuard::quantities(bool cartesian) const noexcept {
  return passivity_.enabled && cartesian ? model::Quantity::kPose : model::Quantity::kNone;
}

void GainGuard::reset(const CommandBus& command, const model::Data& data, const JointState& state,
                      Diagnostics& diagnostics) noexcept {
  law_ = command;
  tank_.reset(data, state);
  pending_ = false;
  tank_.cacheBounds(law_);
  fraction_ = 1.0;
  target_stiffness_ = stiffnessOf(command);
  from_distance_ = 0.0;
  if (const auto* cartesian = std::get_if<Cartesian>(&command)) {
    target_frame_ = frameOf(cartesian->task_frame);
  }
  from_angle_ = 0.0;
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
          if (passivity_.enabled) {  // the tank pays for a move of the target (update())
            copy(law.nullspace_position, in_force.nullspace_position, COMPLY_MAX_DOF);
          }
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
  tank_.beginCycle();
  // Once the gains in force are the command's, nothing moves them until the next command: the
  // common cycle then only keeps the refill window.
  const auto* cartesian = std::get_if<Cartesian>(&command);
  if (pending_) {
    pending_ = cartesian != nullptr ? !updateCartesian(*cartesian, data, state, period_s)
                                    : !updateJoint(*std::get_if<Joint>(&command), state, period_s);
    tank_.cacheBounds(law_);
    fraction_ = gainFraction();
  }
  if (passivity_.enabled) {
    if (cartesian != nullptr) {
      tank_.refillCartesian(*std::get_if<Cartesian>(&law_), data, period_s, torque_clipped);
    } else {
      tank_.refillJoint(*std::get_if<Joint>(&law_), state, period_s, torque_clipped);
    }
  }
  publish(diagnostics);
}

bool GainGuard::updateCartesian(const Cartesian& target, const model::Data& data,
                                const JointState& state, double period_s) noexcept {
  auto& law = *std::get_if<Cartesian>(&law_);
  bool arrived = approachDampings(law, target, ramps_, period_s);
  const TaskStiffness in_force = TaskStiffness::of(law);
  TaskStiffness candidate;
  JointVector nullspace_candidate(target.dof);
  arrived &=
      stiffnessCandidate(law, in_force, target, ramps_, period_s, candidate, nullspace_candidate);
  // What the tank pays: the task account first, then the nullspace's.
  double beta = 1.0;
  double nullspace_beta = 1.0;
  if (passivity_.enabled) {
    beta = tank_.payTaskChange(law, data, in_force, candidate);
    nullspace_beta = tank_.payNullspaceChange(law, state, nullspace_candidate);
  }
  applyStiffness(law, target, in_force, candidate, beta, nullspace_candidate, nullspace_beta);
  // Then a move of the nullspace target, at the nullspace stiffness now in force; a target that
  // has not moved costs nothing and touches nothing.
  double move_beta = 1.0;
  const int dof = target.dof;
  if (passivity_.enabled && !std::equal(law.nullspace_position, law.nullspace_position + dof,
                                        target.nullspace_position)) {
    const JointVector to = Eigen::Map<const JointVector>(target.nullspace_position, dof);
    move_beta = tank_.payNullspaceMove(law, state, to);
    blend(law.nullspace_position, to.data(), dof, move_beta);
  }
  return arrived && beta == 1.0 && nullspace_beta == 1.0 && move_beta == 1.0;
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
    beta = tank_.payJointChange(law, state, candidate);
  }
  blend(law.stiffness, candidate.data(), dof, beta);
  return arrived && beta == 1.0;
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
  diagnostics.tank_energy_j.store(passivity_.enabled ? tank_.task().energy_j : 0.0, kRelaxed);
  diagnostics.nullspace_tank_energy_j.store(passivity_.enabled ? tank_.nullspace().energy_j : 0.0,
                                            kRelaxed);
  diagnostics.injected_j.store(tank_.injected(), kRelaxed);
  diagnostics.dissipated_j.store(tank_.dissipated(), kRelaxed);
  diagnostics.refused_j.store(tank_.refused(), kRelaxed);
  diagnostics.gain_fraction.store(fraction_, kRelaxed);
}

}  // namespace comply::pipeline
