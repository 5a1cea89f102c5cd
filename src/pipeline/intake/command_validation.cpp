#include "comply/pipeline/command_validation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "comply/core/number_text.hpp"
#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

Verdict reject(RejectionReason reason, const std::string& message) {
  return {false, reason, std::string(toString(reason)) + ": " + message};
}

RejectionReason reasonFor(schema::Violation violation) {
  switch (violation) {
    case schema::Violation::kWrongSize:
      return RejectionReason::kDofMismatch;
    case schema::Violation::kNotUnit:
      return RejectionReason::kInvalidQuaternion;
    case schema::Violation::kNegative:
    case schema::Violation::kNotSymmetricPsd:
    case schema::Violation::kGainTooLarge:
      return RejectionReason::kInvalidGains;
    case schema::Violation::kValueTooLarge:
    case schema::Violation::kNotSelection:
    case schema::Violation::kNegativeThreshold:
      return RejectionReason::kOutOfRange;
    case schema::Violation::kNone:
    case schema::Violation::kNonFinite:
      break;
  }
  return RejectionReason::kNonFinite;
}

/// The checks both kinds share: the stamp, then the fields.
template <typename Command>
Verdict checkStampAndFields(Command& incoming, const ValidationConfig& limits, int dof,
                            double last_stamp_s) {
  if (!std::isfinite(incoming.stamp_s)) {
    return reject(RejectionReason::kNonFinite, "stamp");
  }
  if (incoming.stamp_s < last_stamp_s) {
    return reject(RejectionReason::kStaleStamp, "stamp is older than the last accepted command");
  }
  schema::CheckOptions options;
  options.quaternion_tolerance = limits.quaternion_tolerance;
  options.gain_tolerance = limits.gain_tolerance;
  const schema::CheckResult result = schema::checkFields(incoming, dof, options);
  if (!result.ok()) {
    return reject(reasonFor(result.violation), result.message);
  }
  return {};
}

struct Jump {
  double distance = 0.0;  ///< [m]
  double angle = 0.0;     ///< [rad]
  bool force_axes_left_out = false;
};

/// How far `incoming`'s target is from the measured pose, leaving out the axes that stay force
/// axes with it (validateCommand): the largest over the selections in force.
Jump targetJump(const CartesianCommand& incoming, const MeasuredPose& measured,
                std::span<const ForceSelection> in_force) {
  // stableNorm: a target 1e300 m away is reported as that, not as an overflowed infinity.
  const Jump full{(incoming.position - measured.tcp_position).stableNorm(),
                  incoming.orientation.angularDistance(measured.tcp_orientation)};
  if (in_force.empty() && !has(incoming.fields, CommandField::kForce)) {
    return full;
  }
  const ForceSelection none;
  Jump jump;
  for (const ForceSelection& base : in_force.empty() ? std::span(&none, 1) : in_force) {
    const Vector6d& axes =
        has(incoming.fields, CommandField::kForce) ? incoming.force_axes : base.axes;
    if ((axes.array() == 0.0).all()) {
      return full;  // no force axis with this selection: the whole jump counts
    }
    const Eigen::Quaterniond frame =
        has(incoming.fields, CommandField::kTaskFrame) ? incoming.task_frame : base.task_frame;
    // A bus never written (before activation) has a zero quaternion: the base frame.
    const Eigen::Matrix3d task =
        frame.norm() > 0.5 ? frame.normalized().toRotationMatrix() : Eigen::Matrix3d::Identity();
    Eigen::Vector3d linear = task.transpose() * (incoming.position - measured.tcp_position);
    Eigen::Vector3d angular =
        task.transpose() * orientationError(measured.tcp_orientation, incoming.orientation);
    for (int i = 0; i < 3; ++i) {
      linear[i] = axes[i] != 0.0 ? 0.0 : linear[i];
      angular[i] = axes[i + 3] != 0.0 ? 0.0 : angular[i];
    }
    jump.distance = std::max(jump.distance, linear.stableNorm());
    jump.angle = std::max(jump.angle, angular.norm());
    jump.force_axes_left_out = true;
  }
  return jump;
}

template <typename Command>
Verdict validateAndMergeAny(const Command& incoming, const ValidationConfig& limits, int dof,
                            const MeasuredPose& measured, Command& merged) {
  Command checked = incoming;
  Verdict verdict;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    const ForceSelection in_force{merged.force_axes, merged.task_frame};
    verdict = validateCommand(checked, limits, dof, measured, merged.stamp_s, {&in_force, 1});
  } else {
    verdict = validateCommand(checked, limits, dof, measured, merged.stamp_s);
  }
  if (verdict.accepted) {
    schema::merge(merged, checked);
    merged.fields = CommandField::kAll;  // the plugin reads every group
  }
  return verdict;
}

/// The nullspace target against the measured joints (infinity norm), over the joints whose
/// nullspace spring pulls (stiffness above zero): a jump there moves the arm as fast as a joint
/// target's would. Skipped when `measured` carries no joint position (a chunk's later waypoint).
Verdict checkNullspaceJump(const CartesianCommand& incoming, const ValidationConfig& limits,
                           const MeasuredPose& measured) {
  const Eigen::Index count = incoming.nullspace_position.size();
  if (measured.position.size() != count || incoming.nullspace_stiffness.size() != count) {
    return {};
  }
  double jump = 0.0;
  Eigen::Index joint = 0;
  for (Eigen::Index i = 0; i < count; ++i) {
    const double apart = std::abs(incoming.nullspace_position[i] - measured.position[i]);
    if (incoming.nullspace_stiffness[i] > 0.0 && apart > jump) {
      jump = apart;
      joint = i;
    }
  }
  if (jump <= limits.max_nullspace_jump_rad) {
    return {};
  }
  const NumberTexts texts = numbersApart(jump, limits.max_nullspace_jump_rad);
  std::ostringstream text;
  text << "nullspace_position is " << texts.value << " rad from the measured position at joint "
       << joint + 1 << " (limit " << texts.limit << " rad, validation.max_nullspace_jump_rad)";
  return reject(RejectionReason::kPoseJump, text.str());
}

}  // namespace

std::string stampText(std::int64_t stamp_ns) {
  const StampParts parts = splitStamp(stamp_ns);
  const std::string fraction = std::to_string(parts.nanosec);
  return std::to_string(parts.sec) + "." + std::string(9 - fraction.size(), '0') + fraction + " s";
}

MeasuredPose measuredPoseFrom(const JointVector& position, const model::Data& data) noexcept {
  MeasuredPose pose;
  pose.position = position;
  pose.tcp_position = data.tip_position;
  pose.tcp_orientation = data.tip_orientation;
  pose.valid = true;
  return pose;
}

std::string_view toString(RejectionReason reason) {
  return reason == RejectionReason::kCount ? "unknown"
                                           : rejectionReasonName(static_cast<std::size_t>(reason));
}

Verdict validateCommand(CartesianCommand& incoming, const ValidationConfig& limits, int dof,
                        const MeasuredPose& measured, double last_stamp_s,
                        std::span<const ForceSelection> in_force) {
  Verdict verdict = checkStampAndFields(incoming, limits, dof, last_stamp_s);
  if (!verdict.accepted || !measured.valid) {
    return verdict;
  }
  if (has(incoming.fields, CommandField::kNullspace)) {
    verdict = checkNullspaceJump(incoming, limits, measured);
  }
  if (!verdict.accepted || !has(incoming.fields, CommandField::kPosition)) {
    return verdict;
  }
  const auto [distance, angle, left_out] = targetJump(incoming, measured, in_force);
  if (distance > limits.max_position_jump_m || angle > limits.max_orientation_jump_rad) {
    const NumberTexts position = numbersApart(distance, limits.max_position_jump_m);
    const NumberTexts orientation = numbersApart(angle, limits.max_orientation_jump_rad);
    std::ostringstream text;
    text << "target is " << position.value << " m / " << orientation.value
         << " rad from the measured pose" << (left_out ? " off the force axes" : "") << " (limits "
         << position.limit << " m / " << orientation.limit << " rad)";
    return reject(RejectionReason::kPoseJump, text.str());
  }
  return verdict;
}

Verdict validateCommand(JointCommand& incoming, const ValidationConfig& limits, int dof,
                        const MeasuredPose& measured, double last_stamp_s) {
  Verdict verdict = checkStampAndFields(incoming, limits, dof, last_stamp_s);
  if (!verdict.accepted || !has(incoming.fields, CommandField::kPosition) || !measured.valid) {
    return verdict;
  }
  const double jump = (incoming.position - measured.position).cwiseAbs().maxCoeff();
  if (jump > limits.max_joint_jump_rad) {
    const NumberTexts texts = numbersApart(jump, limits.max_joint_jump_rad);
    std::ostringstream text;
    text << "target is " << texts.value << " rad from the measured position (limit " << texts.limit
         << " rad)";
    return reject(RejectionReason::kPoseJump, text.str());
  }
  return verdict;
}

Verdict validateAndMerge(const CartesianCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, CartesianCommand& merged) {
  return validateAndMergeAny(incoming, limits, dof, measured, merged);
}

Verdict validateAndMerge(const JointCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, JointCommand& merged) {
  return validateAndMergeAny(incoming, limits, dof, measured, merged);
}

}  // namespace comply::pipeline
