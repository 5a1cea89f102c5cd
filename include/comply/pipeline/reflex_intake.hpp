#pragma once
// The wrapper's checks for the contact reflex (contact_reflex.hpp), on the intake's side: while
// its hold waits for a reset nothing is taken, and a command's thresholds stay within the file's
// ceilings. Intake side: may allocate.

#include <cstdint>

#include "comply/core/commands.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/contact_reflex.hpp"
#include "comply/pipeline/diagnostics.hpp"

namespace comply::pipeline {

/// Refused as reflex_latched while the cycle's reflex holds (Diagnostics::reflex_latched) and no
/// reset was asked for since it tripped: `trips_at_reset` is Diagnostics::reflex_trips when the
/// last reset was asked for (what follows a reset request in the queue is taken after it).
Verdict checkReflexLatch(const Diagnostics& diagnostics, std::uint64_t trips_at_reset);

/// A command that sets the reflex group: each entry of reflex_force within reflex.max_force_n and
/// of reflex_torque within reflex.max_torque_nm, else out_of_range naming the field, the axis,
/// the value and the ceiling (the schema has refused negative and non-finite entries).
Verdict checkReflexCeilings(const CartesianCommand& command, const ReflexConfig& config);
Verdict checkReflexCeilings(const JointCommand& command, const ReflexConfig& config);

}  // namespace comply::pipeline
