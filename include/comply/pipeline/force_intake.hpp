#pragma once
// The wrapper's checks of a Cartesian command that reach beyond the command itself: its jump
// against the force axes in force (command_validation.hpp) and the wrench it asks the arm to
// exert against what the arm can exert (wrench_bound.hpp). Intake side: may allocate.

#include <string>

#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

/// validateAndMerge() at the wrapper, into `merged` (whose stamp is the floor). Cartesian: the jump
/// check leaves out the force axes in force both as the cycle holds them
/// (controller.commandInForce(): the watchdog may have ended them) and as the intake accepted them
/// (`accepted`: commands queued that the cycle has not taken yet); the larger jump counts, so an
/// axis is left out only where both hold it under force. Then checkWrenches() and
/// checkWorkspace() (workspace_intake.hpp). Joint: validateAndMerge().
Verdict validateAtIntake(const CartesianCommand& incoming, Controller& controller,
                         const MeasuredPose& measured, const CartesianCommand& accepted,
                         CartesianCommand& merged);
Verdict validateAtIntake(const JointCommand& incoming, Controller& controller,
                         const MeasuredPose& measured, const JointCommand& accepted,
                         JointCommand& merged);

/// The wrenches a command asks for, against what the arm exerts at the measured pose: the force
/// target along the axes it selects (task frame: the command's own, else `accepted`'s, turned into
/// the base frame) when it sets the force group, the wrench feedforward when it sets that, and
/// their sum with what stays in force from `accepted`. One above the bound (effort ratio > 1 at the
/// measured pose) is refused as out_of_range, naming the value, the bound along its direction, the
/// joint and the robot. Nothing to check before the arm is measured.
Verdict checkWrenches(const CartesianCommand& incoming, const CartesianCommand& accepted,
                      const Controller& controller, const MeasuredPose& measured);

}  // namespace comply::pipeline
