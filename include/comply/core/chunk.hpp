#pragma once
// A timed action chunk (docs/chunks.md): the waypoints a learned policy emits at once, each with
// its time on the host's clock and a command of the controller's kind. The cycle evaluates the
// chunk at its own time (pipeline/chunk_player.hpp): a C1 curve through the poses, gains and task
// frames interpolated between waypoints, a C2 blend from the reference in force when it starts.

#include <cstdint>
#include <limits>
#include <vector>

#include "comply/core/commands.hpp"

namespace comply {

/// Most waypoints one chunk may carry (policies emit 8-50).
inline constexpr int kMaxChunkWaypoints = 64;

/// The field groups a chunk may drive: every group but the acceleration, which the curve implies.
/// kVelocity gives each waypoint's velocity (twist or joint velocity) instead of the implied one.
inline constexpr CommandField kChunkFields =
    CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness |
    CommandField::kDamping | CommandField::kTaskFrame | CommandField::kWrenchFeedforward |
    CommandField::kTorqueFeedforward | CommandField::kNullspace;

template <typename Command>
struct ChunkWaypoint {
  double time_s = 0.0;  ///< when the reference passes here, on the host's clock [s]
  Command command;      ///< the groups of the chunk's `fields` (its own stamp and fields unused)
};

template <typename Command>
struct Chunk {
  double stamp_s = 0.0;  ///< sender time [s], the same rules as a command's stamp
  /// The groups every waypoint sets; kPosition is required. A group the chunk does not drive
  /// keeps the value in force.
  CommandField fields = CommandField::kPosition;
  std::vector<ChunkWaypoint<Command>> waypoints;  ///< strictly increasing times
  /// The stamp of the observation the sender planned the chunk for, on the host's clock [s]; NaN:
  /// not said. Only reported back (the chunk's timing record): its waypoints carry its times.
  double observation_s = std::numeric_limits<double>::quiet_NaN();
  /// When the chunk takes over from the one playing, on the host's clock [s] (a waypoint's time:
  /// "keep the running chunk until my waypoint m"); NaN: at once.
  double takeover_s = std::numeric_limits<double>::quiet_NaN();
};

using CartesianChunk = Chunk<CartesianCommand>;
using JointChunk = Chunk<JointCommand>;

}  // namespace comply
