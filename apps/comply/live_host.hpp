#pragma once
// The threads of `comply run` around one wrapper and one plant (run_command.cpp sets them up).

#include <atomic>
#include <iosfwd>
#include <memory>

#include "comply/pipeline/resolved_controller.hpp"
#include "run_command.hpp"

namespace comply::app {

/// Runs the host until `stop` is set or options.duration_s has passed; prints a summary on `out`.
/// Returns the process exit code.
int runLiveHost(const RunOptions& options,
                const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                const std::atomic<bool>& stop, std::ostream& out, std::ostream& err);

/// Makes the calling thread SCHED_FIFO at `priority`; "" on success, else why not.
std::string makeRealtime(int priority);

}  // namespace comply::app
