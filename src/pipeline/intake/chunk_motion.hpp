#pragma once
// The motion checks of validateChunk (command_validation.hpp has the rules): what the part of a
// chunk still to play asks of the arm, in speed and acceleration, against the governor's speeds
// and the validation's accelerations. Private to the intake.

#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline {

/// Accepted when the chunk's given velocities, chord speeds (between its waypoints and from the
/// measured pose to the first waypoint ahead) and the curve the cycle will play, blend from
/// `in_force` included (none when null), stay within `arm` and `limits`; else out_of_range with
/// the waypoint, the number and the limit. `chunk` has passed the shape and command checks.
/// `waits`: the chunk waits for its takeover at `host_time_s`, where `in_force` is the reference
/// the cycle will write; its curve joins that reference there (ChunkPlayer::load).
Verdict checkChunkMotion(const CartesianChunk& chunk, int dof, const ValidationConfig& limits,
                         const ChunkLimits& arm, const MeasuredPose& measured, double host_time_s,
                         const CommandBus* in_force, bool waits = false);
Verdict checkChunkMotion(const JointChunk& chunk, int dof, const ValidationConfig& limits,
                         const ChunkLimits& arm, const MeasuredPose& measured, double host_time_s,
                         const CommandBus* in_force, bool waits = false);

}  // namespace comply::pipeline
