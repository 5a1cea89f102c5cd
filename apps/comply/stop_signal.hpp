#pragma once
// Ctrl-C and SIGTERM as a request to stop, for the commands that run until told to.

#include <atomic>

namespace comply::app {

/// Installs the handlers (once more is harmless) and returns the flag they set, cleared.
std::atomic<bool>& stopOnSignals();

}  // namespace comply::app
