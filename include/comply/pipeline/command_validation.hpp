#pragma once
// Validation of incoming commands, on the non-real-time side, before they can reach the cycle.
// A command is merged field group by field group into the last accepted one; a rejected command
// changes nothing.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "comply/core/chunk.hpp"
#include "comply/core/command_reasons.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/config.hpp"

namespace comply::pipeline {

/// The wrapper's reasons (core/command_reasons.hpp has each one's meaning).
enum class RejectionReason : std::uint8_t {
  COMPLY_WRAPPER_REJECTION_REASONS(COMPLY_REASON_ENUMERATOR)  //
  kCount,
};
inline constexpr std::size_t kRejectionReasonCount =
    static_cast<std::size_t>(RejectionReason::kCount);

std::string_view toString(RejectionReason reason);

struct Verdict {
  bool accepted = true;
  RejectionReason reason = RejectionReason::kNonFinite;
  std::string message;         ///< why, with the field name; empty when accepted
  std::uint64_t sequence = 0;  ///< accepted by a wrapper: the number it gave it (CommandId)
};

/// "sec.nanosec s", exact; nanosec in [0, 1e9) as on the wire, also before the epoch.
std::string stampText(std::int64_t stamp_ns);

/// The pose at joint positions `position` from a model update that computed the pose.
MeasuredPose measuredPoseFrom(const JointVector& position, const model::Data& data) noexcept;

/// Force axes in force where a command is checked: the selection (1 = force) and its task frame.
struct ForceSelection {
  Vector6d axes = Vector6d::Zero();
  Eigen::Quaterniond task_frame = Eigen::Quaterniond::Identity();
};

/// Checks `incoming` without merging: stamp (finite, not older than `last_stamp_s`), the fields of
/// the groups it sets (schema::checkFields: sizes, finiteness, unit quaternions, gains) and the
/// jump of its target from `measured`. Renormalises its quaternions in place.
///
/// Along a force axis the reference is not where the arm goes (the force stage puts it on the
/// measured pose every cycle), so the jump check leaves out the target's components along the
/// axes that stay force axes with this command: its own selection when it sets the force group,
/// else each of `in_force`'s (none when empty), in its own task frame when it sets one, else that
/// selection's. Translational and rotational axes alike (the rotation as a rotation vector in the
/// task frame). With several selections in force (the cycle's and the intake's), each is checked
/// and the largest jump counts. An axis a command turns off is checked in full.
Verdict validateCommand(CartesianCommand& incoming, const ValidationConfig& limits, int dof,
                        const MeasuredPose& measured, double last_stamp_s,
                        std::span<const ForceSelection> in_force = {});
Verdict validateCommand(JointCommand& incoming, const ValidationConfig& limits, int dof,
                        const MeasuredPose& measured, double last_stamp_s);

/// validateCommand() and, on success, writes into `merged` the last accepted command updated
/// with the field groups `incoming` sets (quaternions renormalised), carrying every group. On
/// rejection `merged` is untouched. The force axes in force are `merged`'s.
Verdict validateAndMerge(const CartesianCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, CartesianCommand& merged);
Verdict validateAndMerge(const JointCommand& incoming, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, JointCommand& merged);

/// What a chunk's reference may ask of the arm beyond the fixed limits (validateChunk): the
/// speeds are the motion governor's (governor.*), applied whether or not the governor runs in the
/// cycle; the accelerations are ValidationConfig's max_chunk_*. 0, or an empty vector: no bound.
struct ChunkLimits {
  double tcp_speed_m_per_s = 0.0;            ///< governor.tcp_speed_m_per_s (Cartesian chunks)
  double tcp_angular_speed_rad_per_s = 0.0;  ///< governor.tcp_angular_speed_rad_per_s
  /// Per joint (joint chunks): governor.velocity_fraction x the URDF velocity limit [rad/s | m/s].
  JointVector joint_speed;
  /// chunk_blend_time_s: how long the blend from the reference in force lasts (0: none).
  double blend_time_s = 0.0;
};

/// Where a chunk that waits for its takeover time starts from: the reference the cycle will write
/// then (ChunkPlayer::predict), in place of the measured pose and the reference in force now.
struct ChunkTakeover {
  double time_s = 0.0;  ///< the takeover, on the host's clock [s]
  MeasuredPose pose;    ///< the reference's pose then, as a measured pose
  CommandBus reference;
};

/// Checks a timed chunk as a whole at the intake (chunk_validation.cpp), the message naming the
/// waypoint, the number and the limit:
/// - shape: 1 to kMaxChunkWaypoints waypoints; groups within kChunkFields and kPosition among
///   them; finite, strictly increasing times; one damping mode (invalid_chunk, non_finite);
/// - time: the last waypoint after `host_time_s` (the host's clock, the times' timebase;
///   late_chunk), the first not more than limits.max_stamp_lead_s after it (invalid_chunk: a
///   chunk waiting that long would hold the arm for a sender that may be gone);
/// - every waypoint as a command (validateCommand: stamp, fields), the first waypoint not yet
///   past against the measured pose and each later one against the one before it, with the jump
///   limits;
/// - motion (chunk_motion.cpp; out_of_range), over the part of the chunk still to play: each
///   waypoint's given velocity, each segment's chord speed (distance over time), the chord from
///   the measured pose to the first waypoint ahead (over its time, at least the blend's), and
///   the curve the cycle will play (the cubic Hermite through the waypoints, its lead-in, and the
///   blend from `in_force`, the reference in force, over arm.blend_time_s), sampled, against the
///   speeds of `arm` and the accelerations of `limits`. Cartesian chunks are held to the TCP's
///   speeds, joint chunks to each joint's.
/// - a takeover time (Chunk::takeover_s), when given: finite, from the first waypoint to the last,
///   not more than limits.max_stamp_lead_s ahead; such a chunk is held to the motion from
///   `takeover` (the reference the cycle will write then) rather than from now.
/// Renormalises quaternions in place. `in_force` null: no blend is checked.
Verdict validateChunk(CartesianChunk& chunk, const ValidationConfig& limits, int dof,
                      const MeasuredPose& measured, double last_stamp_s, double host_time_s,
                      const ChunkLimits& arm = {}, const CommandBus* in_force = nullptr,
                      const ChunkTakeover* takeover = nullptr);
Verdict validateChunk(JointChunk& chunk, const ValidationConfig& limits, int dof,
                      const MeasuredPose& measured, double last_stamp_s, double host_time_s,
                      const ChunkLimits& arm = {}, const CommandBus* in_force = nullptr,
                      const ChunkTakeover* takeover = nullptr);

}  // namespace comply::pipeline
