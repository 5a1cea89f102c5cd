// Stage "reflex" (contact_reflex.hpp): the contact wrench against the thresholds of the command
// in force, and the reaction the file asks for in the cycle it trips. It writes the command in
// force itself (the hold, the retreat's reference), so that the state, the recording and a
// reset all see what the arm is held to. Off, it costs one branch.

#include <algorithm>
#include <iterator>

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {
namespace {

/// The task frame's orientation in the base frame: the command's, or the base frame (joint
/// control, or a bus never written, whose quaternion is zero).
Eigen::Quaterniond taskOrientation(const CommandBus& bus) noexcept {
  if (const auto* cartesian = std::get_if<comply_cartesian_command>(&bus)) {
    const Eigen::Quaterniond frame = schema::fromXyzw(cartesian->task_frame);
    if (frame.norm() > 0.5) {
      return frame.normalized();
    }
  }
  return Eigen::Quaterniond::Identity();
}

/// The stiffness of `bus` scaled by `fraction` (the nullspace's stays: it holds the posture).
void scaleStiffness(CommandBus& bus, double fraction) noexcept {
  std::visit(
      [fraction](auto& typed) noexcept {
        if constexpr (requires { typed.stiffness_translational; }) {
          for (int i = 0; i < 9; ++i) {
            typed.stiffness_translational[i] *= fraction;
            typed.stiffness_rotational[i] *= fraction;
          }
        } else {
          for (int i = 0; i < typed.dof; ++i) {
            typed.stiffness[i] *= fraction;
          }
        }
      },
      bus);
}

}  // namespace

bool Controller::contactAllowance(double& force_n, double& torque_n_m) const noexcept {
  if (!reflex_.enabled()) {
    return false;
  }
  const ReflexThresholds thresholds = std::visit(
      [this](const auto& typed) noexcept {
        return reflex_.thresholds(typed.reflex_force, typed.reflex_torque);
      },
      active_);
  force_n = thresholds.force_n.maxCoeff();
  torque_n_m = thresholds.torque_nm.maxCoeff();
  return true;
}

bool Controller::checkContact() noexcept {
  if (!reflex_.enabled()) {
    return true;
  }
  if (reflex_.latched()) {
    retreatFromContact();
    return true;
  }
  const ReflexThresholds thresholds = std::visit(
      [this](const auto& typed) noexcept {
        return reflex_.thresholds(typed.reflex_force, typed.reflex_torque);
      },
      active_);
  const ContactReflex::Check check = reflex_.check(contactWrench(ForceSource::kAuto),
                                                   taskOrientation(active_), thresholds, period_s_);
  if (check == ContactReflex::Check::kArmed) {
    return true;
  }
  if (check == ContactReflex::Check::kNoEstimate) {
    enterFault("reflex: ", reflex_.detail());
    return false;
  }
  diagnostics_.reflex_trips.fetch_add(1, std::memory_order_relaxed);
  if (reflex_.config().reaction == ReflexReaction::kFault) {
    enterFault("reflex: ", reflex_.detail());
    return false;
  }
  // Hold: what the arm does now is what it keeps doing, slowly and softly; nothing a command asked
  // for goes on. A chunk ends here; a waiting one is dropped.
  chunks_.stop();
  const MeasuredPose pose = currentPose();
  holdMeasured(active_, pose);
  scaleStiffness(active_, reflex_.config().hold_stiffness_fraction);
  reflex_trip_s_ = time_s_;
  reflex_.startRetreat(pose.tcp_position);
  diagnostics_.reflex_latched.store(true, std::memory_order_relaxed);
  publishInForce();
  return true;
}

void Controller::retreatFromContact() noexcept {
  auto* cartesian = std::get_if<comply_cartesian_command>(&active_);
  if (cartesian == nullptr || reflex_.config().reaction != ReflexReaction::kRetreat) {
    return;
  }
  Eigen::Vector3d position;
  Eigen::Vector3d velocity;
  reflex_.retreat(time_s_ - reflex_trip_s_, position, velocity);
  const Eigen::Map<Eigen::Vector3d> reference(cartesian->position);
  const Eigen::Map<Eigen::Vector3d> twist(cartesian->twist);
  if (reference == position && twist == velocity) {
    return;  // held at the end: the command in force is already this
  }
  Eigen::Map<Eigen::Vector3d>(cartesian->position) = position;
  Eigen::Map<Eigen::Vector3d>(cartesian->twist) = velocity;
  publishInForce();
}

void Controller::rearmReflex() noexcept {
  reflex_.reset();
  diagnostics_.reflex_latched.store(false, std::memory_order_relaxed);
  // The phase that raised them is over: a reset starts from the file's thresholds.
  std::visit(
      [](auto& typed) noexcept {
        std::fill(std::begin(typed.reflex_force), std::end(typed.reflex_force), 0.0);
        std::fill(std::begin(typed.reflex_torque), std::end(typed.reflex_torque), 0.0);
      },
      active_);
}

}  // namespace comply::pipeline
