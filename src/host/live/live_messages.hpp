#pragma once
// The diagnostics message of `comply run` (the state's is in state_sample.hpp), built on its
// publisher thread from what the control thread and the intake report.

#include <string>
#include <vector>

#include "comply/pipeline/resolved_controller.hpp"
#include "comply/transport/messages.hpp"
#include "live_intake.hpp"
#include "live_observer.hpp"

namespace comply::host {

/// The counters of the wrapper, the loop and the intake, with `outcomes` attached.
transport::DiagnosticsMessage diagnosticsMessage(
    const pipeline::DiagnosticsSnapshot& wrapper, const LoopCounters& loop, double period_s,
    const pipeline::GateCounts& counts, std::uint64_t publisher, const std::string& host_name,
    std::vector<transport::CommandOutcomeMessage> outcomes);

}  // namespace comply::host
