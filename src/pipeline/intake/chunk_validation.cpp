// validateChunk (command_validation.hpp): a chunk is checked as a whole before any of it can
// reach the cycle, so a chunk with one bad waypoint changes nothing.

#include <cmath>
#include <iomanip>
#include <sstream>

#include "chunk_motion.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

Verdict reject(RejectionReason reason, const std::string& message) {
  return {false, reason, std::string(toString(reason)) + ": " + message};
}

/// The pose a waypoint's target is compared with: the measured one for the first waypoint not
/// yet past, the waypoint before it for the others.
MeasuredPose poseOf(const CartesianCommand& command) {
  MeasuredPose pose;
  pose.tcp_position = command.position;
  pose.tcp_orientation = command.orientation;
  pose.valid = true;
  return pose;
}
MeasuredPose poseOf(const JointCommand& command) {
  MeasuredPose pose;
  pose.position = command.position;
  pose.valid = true;
  return pose;
}

std::string groupNames(CommandField fields) {
  std::string names;
  for (const schema::GroupInfo& group : schema::groups()) {
    if (has(fields, group.field)) {
      names += (names.empty() ? "" : ", ") + std::string(group.name);
    }
  }
  return names;
}

/// A time on the host's clock [s], to the millisecond.
std::string timeText(double time_s) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << time_s << " s";
  return text.str();
}

/// The takeover time, when given, and the observation's: times a stamp can carry; the takeover
/// one of the chunk's own and not further ahead than a chunk may start.
template <typename Command>
Verdict checkTakeover(const Chunk<Command>& chunk, double host_time_s, double max_lead_s) {
  if (std::isinf(chunk.observation_s)) {
    return reject(RejectionReason::kNonFinite, "the observation time is not finite");
  }
  const double takeover_s = chunk.takeover_s;
  if (std::isnan(takeover_s)) {
    return {};
  }
  if (!std::isfinite(takeover_s)) {
    return reject(RejectionReason::kNonFinite, "the takeover time is not finite");
  }
  const double first_s = chunk.waypoints.front().time_s;
  const double last_s = chunk.waypoints.back().time_s;
  if (takeover_s < first_s || takeover_s > last_s) {
    return reject(RejectionReason::kInvalidChunk,
                  "its takeover at " + timeText(takeover_s) + " is outside its waypoints (" +
                      timeText(first_s) + " to " + timeText(last_s) + ")");
  }
  if (std::isfinite(host_time_s) && takeover_s - host_time_s > max_lead_s) {
    std::ostringstream ahead;
    ahead << "its takeover at " << timeText(takeover_s) << " is " << takeover_s - host_time_s
          << " s ahead of the host's clock (at most " << max_lead_s
          << " s: validation.max_stamp_lead_s)";
    return reject(RejectionReason::kInvalidChunk, ahead.str());
  }
  return {};
}

/// The rules of a chunk's shape and time; accepted when they hold.
template <typename Command>
Verdict checkShape(const Chunk<Command>& chunk, double host_time_s, double max_lead_s) {
  const std::size_t count = chunk.waypoints.size();
  if (count == 0 || count > static_cast<std::size_t>(kMaxChunkWaypoints)) {
    return reject(RejectionReason::kInvalidChunk,
                  "a chunk carries 1 to " + std::to_string(kMaxChunkWaypoints) +
                      " waypoints, this one " + std::to_string(count));
  }
  if (!has(chunk.fields, CommandField::kPosition)) {
    return reject(RejectionReason::kInvalidChunk, "a chunk's waypoints must set the position");
  }
  const auto outside = static_cast<CommandField>(static_cast<std::uint32_t>(chunk.fields) &
                                                 ~static_cast<std::uint32_t>(kChunkFields));
  if (outside != CommandField::kNone) {
    // The acceleration follows from the curve through the waypoints; force axes, the reflex's
    // thresholds and a workspace box are modes, not quantities to interpolate: a command sets them.
    return reject(RejectionReason::kInvalidChunk,
                  "a chunk cannot set " + groupNames(outside) +
                      " (the acceleration follows from the curve through the waypoints; force "
                      "axes, reflex thresholds and a workspace box come with a command, and last "
                      "through the chunks after it)");
  }
  for (std::size_t k = 0; k < count; ++k) {
    const double t = chunk.waypoints[k].time_s;
    if (!std::isfinite(t)) {
      return reject(RejectionReason::kNonFinite,
                    "waypoint " + std::to_string(k) + " time is not finite");
    }
    if (k > 0 && !(t > chunk.waypoints[k - 1].time_s)) {
      return reject(RejectionReason::kInvalidChunk,
                    "waypoint " + std::to_string(k) + "'s time is not after waypoint " +
                        std::to_string(k - 1) + "'s (times must increase strictly)");
    }
  }
  const double last_s = chunk.waypoints.back().time_s;
  if (std::isfinite(host_time_s) && last_s <= host_time_s) {
    std::ostringstream late;
    late << host_time_s - last_s;
    return reject(RejectionReason::kLateChunk, "its last waypoint was due " + late.str() +
                                                   " s ago on the host's clock; nothing of it is "
                                                   "left to play");
  }
  if (Verdict takeover = checkTakeover(chunk, host_time_s, max_lead_s); !takeover.accepted) {
    return takeover;
  }
  const double lead_s = chunk.waypoints.front().time_s - host_time_s;
  if (std::isfinite(host_time_s) && lead_s > max_lead_s) {
    // A chunk waiting that long holds the arm's reference for a sender that may be gone.
    std::ostringstream ahead;
    ahead << "waypoint 0 at " << timeText(chunk.waypoints.front().time_s) << " is due " << lead_s
          << " s ahead of the host's clock (at most " << max_lead_s
          << " s: validation.max_stamp_lead_s; the host's clock is at " << timeText(host_time_s)
          << ")";
    return reject(RejectionReason::kInvalidChunk, ahead.str());
  }
  return {};
}

template <typename Command>
Verdict validateChunkAny(Chunk<Command>& chunk, const ValidationConfig& limits, int dof,
                         const MeasuredPose& measured, double last_stamp_s, double host_time_s,
                         const ChunkLimits& arm, const CommandBus* in_force,
                         const ChunkTakeover* takeover) {
  if (!std::isfinite(chunk.stamp_s)) {
    return reject(RejectionReason::kNonFinite, "stamp");
  }
  if (Verdict shape = checkShape(chunk, host_time_s, limits.max_stamp_lead_s); !shape.accepted) {
    return shape;
  }
  // A chunk that waits for its takeover is held to the motion from there.
  const MeasuredPose& from = takeover != nullptr ? takeover->pose : measured;
  const double from_s = takeover != nullptr ? takeover->time_s : host_time_s;
  const CommandBus* reference = takeover != nullptr ? &takeover->reference : in_force;
  bool compared_with_measured = false;
  for (std::size_t k = 0; k < chunk.waypoints.size(); ++k) {
    ChunkWaypoint<Command>& waypoint = chunk.waypoints[k];
    waypoint.command.stamp_s = chunk.stamp_s;
    waypoint.command.fields = chunk.fields;
    const bool past = waypoint.time_s <= from_s;
    MeasuredPose against;  // invalid: no jump check (a past waypoint after a past one)
    if (!past && !compared_with_measured) {
      against = from;
      compared_with_measured = true;
    } else if (k > 0) {
      against = poseOf(chunk.waypoints[k - 1].command);
    }
    Verdict verdict = validateCommand(waypoint.command, limits, dof, against, last_stamp_s);
    if (!verdict.accepted) {
      verdict.message = "waypoint " + std::to_string(k) + ": " + verdict.message;
      return verdict;
    }
    if constexpr (std::is_same_v<Command, CartesianCommand>) {
      if (has(chunk.fields, CommandField::kDamping) &&
          waypoint.command.damping_mode != chunk.waypoints[0].command.damping_mode) {
        return reject(RejectionReason::kInvalidChunk,
                      "waypoint " + std::to_string(k) +
                          ": its damping mode differs from waypoint 0's (one mode per chunk)");
      }
    }
  }
  return checkChunkMotion(chunk, dof, limits, arm, from, from_s, reference, takeover != nullptr);
}

}  // namespace

Verdict validateChunk(CartesianChunk& chunk, const ValidationConfig& limits, int dof,
                      const MeasuredPose& measured, double last_stamp_s, double host_time_s,
                      const ChunkLimits& arm, const CommandBus* in_force,
                      const ChunkTakeover* takeover) {
  return validateChunkAny(chunk, limits, dof, measured, last_stamp_s, host_time_s, arm, in_force,
                          takeover);
}

Verdict validateChunk(JointChunk& chunk, const ValidationConfig& limits, int dof,
                      const MeasuredPose& measured, double last_stamp_s, double host_time_s,
                      const ChunkLimits& arm, const CommandBus* in_force,
                      const ChunkTakeover* takeover) {
  return validateChunkAny(chunk, limits, dof, measured, last_stamp_s, host_time_s, arm, in_force,
                          takeover);
}

}  // namespace comply::pipeline
