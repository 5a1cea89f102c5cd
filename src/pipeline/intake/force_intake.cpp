#include "comply/pipeline/force_intake.hpp"

#include <array>
#include <sstream>

#include "comply/core/number_text.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/workspace_intake.hpp"
#include "comply/pipeline/wrench_bound.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

/// The force target along the selected axes of `command`, in the base frame (force first).
Vector6d targetInBase(const CartesianCommand& command, const Eigen::Quaterniond& task_frame) {
  const Vector6d target = command.wrench_target.cwiseProduct(
      (command.force_axes.array() != 0.0).cast<double>().matrix());
  // A bus never written (before activation) has a zero quaternion: the base frame.
  const Eigen::Matrix3d task = task_frame.norm() > 0.5 ? task_frame.normalized().toRotationMatrix()
                                                       : Eigen::Matrix3d::Identity();
  Vector6d base;
  base.head<3>().noalias() = task * target.head<3>();
  base.tail<3>().noalias() = task * target.tail<3>();
  return base;
}

/// One wrench against the bound; `what` names it in the message.
Verdict checkOne(const char* what, const Vector6d& wrench, const model::Data& data,
                 const Controller& controller) {
  const EffortRatio effort =
      effortRatio(data.jacobian, wrench, controller.effortLimit(), controller.dof());
  if (!(effort.ratio > 1.0)) {
    return {};
  }
  const auto joint = static_cast<std::size_t>(effort.joint);
  const double limit = controller.effortLimit()[effort.joint];
  const NumberTexts force =
      numbersApart(wrench.head<3>().norm(), wrench.head<3>().norm() / effort.ratio);
  const NumberTexts torque =
      numbersApart(wrench.tail<3>().norm(), wrench.tail<3>().norm() / effort.ratio);
  std::ostringstream text;
  text << what << " of " << force.value << " N / " << torque.value << " N m is above what "
       << controller.resolved().robot.name
       << " exerts along it at the measured pose: " << force.limit << " N / " << torque.limit
       << " N m (joint " << controller.model().jointNames()[joint] << " would need "
       << effort.ratio * limit << " N m, effort limit " << limit << " N m)";
  const RejectionReason reason = RejectionReason::kOutOfRange;
  return {false, reason, std::string(toString(reason)) + ": " + text.str()};
}

}  // namespace

Verdict validateAtIntake(const CartesianCommand& incoming, Controller& controller,
                         const MeasuredPose& measured, const CartesianCommand& accepted,
                         CartesianCommand& merged) {
  const ValidationConfig& limits = controller.resolved().config.validation;
  const int dof = controller.dof();
  const auto& cycle = std::get<comply_cartesian_command>(controller.commandInForce());
  const std::array<ForceSelection, 2> in_force{
      ForceSelection{Eigen::Map<const Vector6d>(cycle.force_axes),
                     schema::fromXyzw(cycle.task_frame)},
      ForceSelection{accepted.force_axes, accepted.task_frame}};
  CartesianCommand checked = incoming;
  Verdict verdict = validateCommand(checked, limits, dof, measured, merged.stamp_s, in_force);
  if (verdict.accepted) {
    verdict = checkWrenches(checked, accepted, controller, measured);
  }
  if (verdict.accepted) {
    verdict = checkWorkspace(checked, controller.resolved().parameters, measured);
  }
  if (verdict.accepted) {
    schema::merge(merged, checked);
    merged.fields = CommandField::kAll;  // the plugin reads every group
  }
  return verdict;
}

Verdict validateAtIntake(const JointCommand& incoming, Controller& controller,
                         const MeasuredPose& measured, const JointCommand& /*accepted*/,
                         JointCommand& merged) {
  return validateAndMerge(incoming, controller.resolved().config.validation, controller.dof(),
                          measured, merged);
}

Verdict checkWrenches(const CartesianCommand& incoming, const CartesianCommand& accepted,
                      const Controller& controller, const MeasuredPose& measured) {
  const bool sets_force = has(incoming.fields, CommandField::kForce);
  const bool sets_feedforward = has(incoming.fields, CommandField::kWrenchFeedforward);
  if ((!sets_force && !sets_feedforward) || !measured.valid) {
    return {};
  }
  // The TCP Jacobian at the measured joint positions.
  const model::Model& model = controller.model();
  model::Data data(model);
  const auto n = static_cast<std::size_t>(controller.dof());
  const JointVector rest = JointVector::Zero(controller.dof());
  if (model::update(model, data, {measured.position.data(), n}, {rest.data(), n},
                    model::Quantity::kJacobian) != model::UpdateStatus::kOk) {
    return {};  // no Jacobian at this state: the force stage still bounds what it commands
  }
  const CartesianCommand& force = sets_force ? incoming : accepted;
  const Eigen::Quaterniond task_frame =
      has(incoming.fields, CommandField::kTaskFrame) ? incoming.task_frame : accepted.task_frame;
  const Vector6d target = targetInBase(force, task_frame);
  const Vector6d& feedforward =
      sets_feedforward ? incoming.wrench_feedforward : accepted.wrench_feedforward;
  Verdict verdict;
  if (sets_force) {
    verdict = checkOne("wrench_target", target, data, controller);
  }
  if (verdict.accepted && sets_feedforward) {
    verdict = checkOne("wrench_feedforward", feedforward, data, controller);
  }
  if (verdict.accepted) {
    verdict =
        checkOne("wrench_feedforward + wrench_target", feedforward + target, data, controller);
  }
  return verdict;
}

}  // namespace comply::pipeline
