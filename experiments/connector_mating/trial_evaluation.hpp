#pragma once
// Whether one connector-mating trial seated, and if not why: the peg tip's depth along the socket
// axis and the axial contact force as a force sensor's filter reports it. Also writes the
// per-cycle trace: depth, forces, the peg's and the task axis's angles to the socket axis, the
// tip's distance from it and the reference's lead and lateral lag.

#include <filesystem>

#include "comply/host/sim_session.hpp"
#include "connector_mating/connector_mating_experiment.hpp"
#include "connector_mating/mating_stream.hpp"

namespace comply::experiments::connector_mating {

/// The row of `trial` from its `log`: seated when the tip gets within 1 mm of the seat before the
/// axial force passes `force_limit` [N]. Writes every cycle to `trace_file` (CSV).
ConnectorMatingRow evaluateTrial(const Trial& trial, const host::SimLog& log,
                                 const MatingStream& stream, double force_limit,
                                 const std::filesystem::path& trace_file);

}  // namespace comply::experiments::connector_mating
