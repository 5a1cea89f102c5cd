#pragma once
// What a live host may have of the real-time set-up it asks for (see realtime_grant.cpp).

#include <iosfwd>

#include "comply/host/live_host.hpp"

namespace comply::host {

/// Locks the process's memory (options.lock_memory) and asks whether its threads may run
/// SCHED_FIFO at options.priority. Returns the priority the host's threads and its transport's
/// receive threads then run at: options.priority, or 0 (normal scheduling) when refused. Whatever
/// was refused is said once on `err`: what the host loses and how to grant it.
int grantRealtime(const LiveHostOptions& options, std::ostream& err);

}  // namespace comply::host
