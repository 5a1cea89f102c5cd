#include "comply/pipeline/command_validation.hpp"

#include <cmath>
#include <sstream>

#include "comply/core/gains.hpp"

namespace comply::pipeline {
namespace {

Verdict reject(RejectionReason reason, const std::string& message) {
  return {false, reason, std::string(toString(reason)) + ": " + message};
}

bool finite(const Eigen::Quaterniond& q) {
  return q.coeffs().allFinite();
}

/// Renormalises small drift in place; false when the norm is too far from 1.
bool normaliseQuaternion(Eigen::Quaterniond& q, double tolerance) {
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= tolerance)) {
    return false;
  }
  q.coeffs() /= norm;
  return true;
}

std::string describeNorm(const Eigen::Quaterniond& q) {
  std::ostringstream text;
  text << "norm " << q.norm();
  return text.str();
}

template <typename Vector>
bool nonNegative(const Vector& v) {
  return (v.array() >= 0.0).all();
}

/// First joint-space field set in `c` whose size is not `dof` (the message names it); nullptr if
/// none.
const char* wrongSizeField(const CartesianCommand& c, int dof) {
  const CommandField f = c.fields;
  if (has(f, CommandField::kTorqueFeedforward) && c.torque_feedforward.size() != dof) {
    return "torque_feedforward";
  }
  if (has(f, CommandField::kNullspace)) {
    if (c.nullspace_position.size() != dof) {
      return "nullspace_position";
    }
    if (c.nullspace_stiffness.size() != dof) {
      return "nullspace_stiffness";
    }
    if (c.nullspace_damping.size() != dof) {
      return "nullspace_damping";
    }
  }
  return nullptr;
}

/// First field set in `c` that holds NaN or infinity (the message names it); nullptr if none.
const char* nonFiniteField(const CartesianCommand& c) {
  const CommandField f = c.fields;
  const struct {
    CommandField group;
    bool finite;
    const char* name;
  } checks[] = {
      {CommandField::kPosition, c.position.allFinite(), "position"},
      {CommandField::kPosition, finite(c.orientation), "orientation"},
      {CommandField::kVelocity, c.twist.allFinite(), "twist"},
      {CommandField::kAcceleration, c.acceleration.allFinite(), "acceleration"},
      {CommandField::kStiffness, c.stiffness_translational.allFinite(), "stiffness_translational"},
      {CommandField::kStiffness, c.stiffness_rotational.allFinite(), "stiffness_rotational"},
      {CommandField::kDamping, c.damping_translational.allFinite(), "damping_translational"},
      {CommandField::kDamping, c.damping_rotational.allFinite(), "damping_rotational"},
      {CommandField::kDamping, c.damping_ratio.allFinite(), "damping_ratio"},
      {CommandField::kTaskFrame, finite(c.task_frame), "task_frame"},
      {CommandField::kWrenchFeedforward, c.wrench_feedforward.allFinite(), "wrench_feedforward"},
      {CommandField::kTorqueFeedforward, c.torque_feedforward.allFinite(), "torque_feedforward"},
      {CommandField::kNullspace, c.nullspace_position.allFinite(), "nullspace_position"},
      {CommandField::kNullspace, c.nullspace_stiffness.allFinite(), "nullspace_stiffness"},
      {CommandField::kNullspace, c.nullspace_damping.allFinite(), "nullspace_damping"},
  };
  for (const auto& check : checks) {
    if (has(f, check.group) && !check.finite) {
      return check.name;
    }
  }
  return nullptr;
}

}  // namespace

MeasuredPose measuredPoseFrom(const JointVector& position, const model::Data& data) noexcept {
  MeasuredPose pose;
  pose.position = position;
  pose.tcp_position = data.tip_position;
  pose.tcp_orientation = data.tip_orientation;
  pose.valid = true;
  return pose;
}

std::string_view toString(RejectionReason reason) {
  switch (reason) {
    case RejectionReason::kNonFinite:
      return "non_finite";
    case RejectionReason::kInvalidQuaternion:
      return "invalid_quaternion";
    case RejectionReason::kInvalidGains:
      return "invalid_gains";
    case RejectionReason::kDofMismatch:
      return "dof_mismatch";
    case RejectionReason::kStaleStamp:
      return "stale_stamp";
    case RejectionReason::kPoseJump:
      return "pose_jump";
    case RejectionReason::kQueueFull:
      return "queue_full";
    case RejectionReason::kCount:
      break;
  }
  return "unknown";
}

Verdict validateAndMerge(const CartesianCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, CartesianCommand& merged) {
  const CommandField f = incoming.fields;
  if (!std::isfinite(incoming.stamp_s)) {
    return reject(RejectionReason::kNonFinite, "stamp");
  }
  if (incoming.stamp_s < merged.stamp_s) {
    return reject(RejectionReason::kStaleStamp, "stamp is older than the last accepted command");
  }
  const char* wrong_size = wrongSizeField(incoming, dof);
  if (wrong_size != nullptr) {
    return reject(RejectionReason::kDofMismatch,
                  std::string(wrong_size) + " must have " + std::to_string(dof) + " entries");
  }
  const char* non_finite = nonFiniteField(incoming);
  if (non_finite != nullptr) {
    return reject(RejectionReason::kNonFinite, std::string(non_finite) + " holds NaN or infinity");
  }

  CartesianCommand candidate = merged;
  candidate.stamp_s = incoming.stamp_s;
  if (has(f, CommandField::kPosition)) {
    candidate.position = incoming.position;
    candidate.orientation = incoming.orientation;
    if (!normaliseQuaternion(candidate.orientation, limits.quaternion_tolerance)) {
      return reject(RejectionReason::kInvalidQuaternion,
                    "orientation " + describeNorm(incoming.orientation));
    }
  }
  if (has(f, CommandField::kTaskFrame)) {
    candidate.task_frame = incoming.task_frame;
    if (!normaliseQuaternion(candidate.task_frame, limits.quaternion_tolerance)) {
      return reject(RejectionReason::kInvalidQuaternion,
                    "task_frame " + describeNorm(incoming.task_frame));
    }
  }
  if (has(f, CommandField::kStiffness)) {
    if (!isSymmetricPsd(incoming.stiffness_translational, limits.gain_tolerance,
                        limits.gain_tolerance) ||
        !isSymmetricPsd(incoming.stiffness_rotational, limits.gain_tolerance,
                        limits.gain_tolerance)) {
      return reject(RejectionReason::kInvalidGains,
                    "stiffness blocks must be symmetric positive semi-definite");
    }
    candidate.stiffness_translational = incoming.stiffness_translational;
    candidate.stiffness_rotational = incoming.stiffness_rotational;
  }
  if (has(f, CommandField::kDamping)) {
    if (!isSymmetricPsd(incoming.damping_translational, limits.gain_tolerance,
                        limits.gain_tolerance) ||
        !isSymmetricPsd(incoming.damping_rotational, limits.gain_tolerance,
                        limits.gain_tolerance) ||
        !nonNegative(incoming.damping_ratio)) {
      return reject(RejectionReason::kInvalidGains,
                    "damping blocks must be symmetric positive semi-definite and ratios >= 0");
    }
    candidate.damping_translational = incoming.damping_translational;
    candidate.damping_rotational = incoming.damping_rotational;
    candidate.damping_mode = incoming.damping_mode;
    candidate.damping_ratio = incoming.damping_ratio;
  }
  if (has(f, CommandField::kNullspace)) {
    if (!nonNegative(incoming.nullspace_stiffness) || !nonNegative(incoming.nullspace_damping)) {
      return reject(RejectionReason::kInvalidGains, "nullspace gains must be >= 0");
    }
    candidate.nullspace_position = incoming.nullspace_position;
    candidate.nullspace_stiffness = incoming.nullspace_stiffness;
    candidate.nullspace_damping = incoming.nullspace_damping;
  }
  if (has(f, CommandField::kVelocity)) {
    candidate.twist = incoming.twist;
  }
  if (has(f, CommandField::kAcceleration)) {
    candidate.acceleration = incoming.acceleration;
  }
  if (has(f, CommandField::kWrenchFeedforward)) {
    candidate.wrench_feedforward = incoming.wrench_feedforward;
  }
  if (has(f, CommandField::kTorqueFeedforward)) {
    candidate.torque_feedforward = incoming.torque_feedforward;
  }
  if (has(f, CommandField::kPosition) && measured.valid) {
    const double distance = (candidate.position - measured.tcp_position).norm();
    const double angle = candidate.orientation.angularDistance(measured.tcp_orientation);
    if (distance > limits.max_position_jump_m || angle > limits.max_orientation_jump_rad) {
      std::ostringstream text;
      text << "target is " << distance << " m / " << angle << " rad from the measured pose (limits "
           << limits.max_position_jump_m << " m / " << limits.max_orientation_jump_rad << " rad)";
      return reject(RejectionReason::kPoseJump, text.str());
    }
  }
  candidate.fields = CommandField::kAll;
  merged = candidate;
  return {};
}

Verdict validateAndMerge(const JointCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, JointCommand& merged) {
  const CommandField f = incoming.fields;
  if (!std::isfinite(incoming.stamp_s)) {
    return reject(RejectionReason::kNonFinite, "stamp");
  }
  if (incoming.stamp_s < merged.stamp_s) {
    return reject(RejectionReason::kStaleStamp, "stamp is older than the last accepted command");
  }
  struct Group {
    CommandField field;
    const JointVector& source;
    JointVector& target;
    const char* name;
  };
  JointCommand candidate = merged;
  candidate.stamp_s = incoming.stamp_s;
  const std::array<Group, 6> groups{{
      {CommandField::kPosition, incoming.position, candidate.position, "position"},
      {CommandField::kVelocity, incoming.velocity, candidate.velocity, "velocity"},
      {CommandField::kAcceleration, incoming.acceleration, candidate.acceleration, "acceleration"},
      {CommandField::kStiffness, incoming.stiffness, candidate.stiffness, "stiffness"},
      {CommandField::kDamping, incoming.damping, candidate.damping, "damping"},
      {CommandField::kTorqueFeedforward, incoming.torque_feedforward, candidate.torque_feedforward,
       "torque_feedforward"},
  }};
  for (const Group& group : groups) {
    if (!has(f, group.field)) {
      continue;
    }
    if (group.source.size() != dof) {
      return reject(RejectionReason::kDofMismatch,
                    std::string(group.name) + " has " + std::to_string(group.source.size()) +
                        " entries, the controller has " + std::to_string(dof) + " joints");
    }
    if (!group.source.allFinite()) {
      return reject(RejectionReason::kNonFinite,
                    std::string(group.name) + " holds NaN or infinity");
    }
    group.target = group.source;
  }
  if (!nonNegative(candidate.stiffness) || !nonNegative(candidate.damping)) {
    return reject(RejectionReason::kInvalidGains, "joint stiffness and damping must be >= 0");
  }
  if (has(f, CommandField::kPosition) && measured.valid) {
    const double jump = (candidate.position - measured.position).cwiseAbs().maxCoeff();
    if (jump > limits.max_joint_jump_rad) {
      std::ostringstream text;
      text << "target is " << jump << " rad from the measured position (limit "
           << limits.max_joint_jump_rad << " rad)";
      return reject(RejectionReason::kPoseJump, text.str());
    }
  }
  candidate.fields = CommandField::kAll;
  merged = candidate;
  return {};
}

}  // namespace comply::pipeline
