#pragma once
// `comply run`: the controller host. The control loop runs the wrapper on the hardware at the
// control rate on a real-time thread; DDS threads feed it commands and publish its state and
// diagnostics (ROS 2 topics under /<name>/, see transport/endpoints.hpp).

#include <iosfwd>
#include <string>

#include "comply/host/live_host.hpp"

namespace comply::app {

using RunOptions = host::LiveHostOptions;

/// Runs until SIGINT or SIGTERM (or duration_s), then deactivates, flushes and returns 0; 2 on
/// bad options or setup.
int runCommand(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
