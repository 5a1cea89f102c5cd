#pragma once
// The intake's check of a box a command sets for the TCP (the workspace group; virtual_walls.hpp
// keeps the TCP inside it in the cycle). Intake side: may allocate.

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

/// A command that sets the workspace group: all 0 (no box) is taken; otherwise refused as
/// invalid_workspace, naming what is wrong, when along some axis workspace_min is not below
/// workspace_max, when the measured TCP lies farther outside the box than the barrier's braking
/// zone (wall.brake_distance_m: a box must hold the arm, not yank it somewhere), or when the box
/// leaves no room inside the controller file's walls and boxes. The schema has refused non-finite
/// entries.
Verdict checkWorkspace(const CartesianCommand& command, const CycleParameters& parameters,
                       const MeasuredPose& measured);

}  // namespace comply::pipeline
