#pragma once
// What became of one accepted chunk in the cycle (docs/policies.md): when it took over, how many of
// its waypoints were already past (the delay a policy that acted on an observation measures in its
// own steps), how far the reference jumped at the seam, and whether the arm had come to rest
// waiting for it. The player writes one record per chunk on the real-time thread (a plain value,
// no allocation); hosts put it in the chunk's outcome and in the recording.

#include <cstdint>
#include <limits>

namespace comply::pipeline {

/// How a chunk's time in the cycle ended.
enum class ChunkEnd : std::uint8_t {
  kTookOver = 0,    ///< it took over from the reference in force (and plays, or played)
  kSuperseded = 1,  ///< it waited for its takeover time and a newer chunk replaced it first
  kDropped = 2,     ///< it waited and was dropped: a command, a reset, its sender left, a FAULT
};

struct ChunkTiming {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

  std::uint64_t sequence = 0;  ///< the chunk's number (CommandId::sequence)
  ChunkEnd end = ChunkEnd::kTookOver;
  // Times on the controller's clock [s] (hosts map them onto theirs).
  double observation_s = kNone;  ///< the observation the sender planned it for (NaN: not said)
  double received_s = kNone;     ///< when the intake accepted it
  /// When it took over (NaN: it never did): the cycle it took over in, or, for one that waited
  /// for its takeover, that time itself (the curves join there; the next cycle is the first to
  /// play it).
  double takeover_s = kNone;
  double requested_takeover_s = kNone;  ///< the takeover it asked for (NaN: at once)
  double first_waypoint_s = kNone;
  double last_waypoint_s = kNone;
  int waypoints = 0;
  /// Waypoints whose time was already past (by more than a nanosecond) at its takeover: for a
  /// chunk planned on an observation with waypoint 0 at the observation's time, the delay in the
  /// chunk's own steps. The first of the rest is the one the reference reached (for `keep=m`: m).
  int waypoints_past = 0;
  /// The reference's jump at the seam: the difference between the reference in force and the
  /// chunk's own curve at its takeover, which the blend then lets decay. Cartesian:
  /// position [m], orientation [rad], velocity [m/s], angular velocity [rad/s]; joint: the largest
  /// joint's position [rad] and velocity [rad/s], the rotational pair 0.
  double position_jump = 0.0;
  double rotation_jump = 0.0;
  double velocity_jump = 0.0;
  double angular_velocity_jump = 0.0;
  /// The chunk before it had run out before it took over (starvation: the reference came to rest
  /// on its last waypoint), `rest_s` before [s]. False for the first chunk after a command.
  bool starved = false;
  double rest_s = 0.0;
};

}  // namespace comply::pipeline
