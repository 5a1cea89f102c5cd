#pragma once
// Why a command is refused, declared once: the wrapper's reasons (its own checks) and then the
// command gate's (the host's rules). pipeline::RejectionReason and pipeline::CommandReason, the
// wire's transport::Reason, the names every host prints and the CommandOutcome.REASON_* constants
// (msg/CommandOutcome.msg, `make generated`) follow these rows; their numbers are their order.
//
// A row: X(enumerator, name, doc)

// clang-format off
#define COMPLY_WRAPPER_REJECTION_REASONS(X) \
  X(kNonFinite, non_finite, "NaN or infinity in a field that was set") \
  X(kInvalidQuaternion, invalid_quaternion, "orientation or task frame too far from unit norm") \
  X(kInvalidGains, invalid_gains, \
    "stiffness/damping not symmetric positive semi-definite, negative, or above what the arm renders") \
  X(kDofMismatch, dof_mismatch, "joint vectors of the wrong size") \
  X(kStaleStamp, stale_stamp, "stamp not newer than the last accepted command") \
  X(kPoseJump, pose_jump, "target too far from the measured pose / joint position") \
  X(kQueueFull, queue_full, "the cycle has not taken the commands queued before (sender too fast)") \
  X(kOutOfRange, out_of_range, \
    "a rate or feedforward entry above the limit of its unit for any arm; a chunk faster than the arm's speeds or accelerations") \
  X(kLateChunk, late_chunk, "a chunk whose last waypoint is already past on the host's clock") \
  X(kInvalidChunk, invalid_chunk, \
    "a chunk's shape: waypoint count (1 to 64), times (a start more than max_stamp_lead_s ahead), field groups, damping modes") \
  X(kReflexLatched, reflex_latched, \
    "the contact reflex tripped and holds the arm (ControllerState.reflex_tripped): nothing is taken until a reset request") \
  X(kInvalidWorkspace, invalid_workspace, \
    "a workspace box with a corner not below the other, the TCP outside it, or no room inside the controller file's walls")

#define COMPLY_GATE_REJECTION_REASONS(X) \
  X(kOtherPublisher, other_publisher, "another sender holds the command topics") \
  X(kWrongKind, wrong_kind, "a joint command to a Cartesian controller, or the reverse") \
  X(kInactive, inactive, "the controller is not active (or the host stopped before a cycle took it)") \
  X(kFutureStamp, future_stamp, "stamped more than max_stamp_lead_s ahead of the host's clock") \
  X(kInvalidStamp, invalid_stamp, "header.stamp.nanosec not below 1e9") \
  X(kTooLarge, too_large, \
    "a field over its bound where the transport reads it: header.frame_id over 256 bytes, a message over 16 MB")

#define COMPLY_REJECTION_REASONS(X) \
  COMPLY_WRAPPER_REJECTION_REASONS(X) \
  COMPLY_GATE_REJECTION_REASONS(X)
// clang-format on

#define COMPLY_REASON_ENUMERATOR(enumerator, name, doc) enumerator,
#define COMPLY_REASON_COUNT(enumerator, name, doc) +1
#define COMPLY_REASON_NAME(enumerator, name, doc) #name,
#define COMPLY_REASON_DOC(enumerator, name, doc) doc,

#include <array>
#include <cstddef>
#include <string_view>

namespace comply {

inline constexpr std::size_t kWrapperRejectionReasonCount =
    0 COMPLY_WRAPPER_REJECTION_REASONS(COMPLY_REASON_COUNT);
inline constexpr std::size_t kAllRejectionReasonCount =
    0 COMPLY_REJECTION_REASONS(COMPLY_REASON_COUNT);

/// Each reason's name by its number ("non_finite", ...).
inline constexpr std::array<std::string_view, kAllRejectionReasonCount> kRejectionReasonNames{
    COMPLY_REJECTION_REASONS(COMPLY_REASON_NAME)};

/// What each reason means, by its number.
inline constexpr std::array<std::string_view, kAllRejectionReasonCount> kRejectionReasonDocs{
    COMPLY_REJECTION_REASONS(COMPLY_REASON_DOC)};

/// The name of reason number `number`; "none" for 255 (applied), "unknown" for others.
constexpr std::string_view rejectionReasonName(std::size_t number) noexcept {
  if (number < kRejectionReasonNames.size()) {
    return kRejectionReasonNames[number];
  }
  return number == 255 ? "none" : "unknown";
}

}  // namespace comply
