#pragma once
// What a live host may have of the real-time set-up it asks for (see realtime_grant.cpp).

#include <functional>
#include <iosfwd>

#include "comply/host/live_host.hpp"

namespace comply::host {

/// Locks the process's memory (options.lock_memory) and asks whether its threads may run
/// SCHED_FIFO at options.priority. Returns the priority the host's threads and its transport's
/// receive threads then run at: options.priority, the user's rtprio limit when that is below it
/// and granted, or 0 (normal scheduling) when refused. Whatever was refused or lowered is said
/// once on `err`: what the host loses and how to grant it.
int grantRealtime(const LiveHostOptions& options, std::ostream& err);

/// Whether this process holds `capability` (CAP_*) in its effective set.
bool hasEffectiveCapability(int capability);

/// The SCHED_FIFO priority to run at when `asked` (> 0) may be had or not (`granted`): `asked`;
/// else `rtprio_limit` (the user's RLIMIT_RTPRIO) when it is between 1 and `asked` and granted;
/// else 0.
int grantablePriority(int asked, long long rtprio_limit, const std::function<bool(int)>& granted);

}  // namespace comply::host
