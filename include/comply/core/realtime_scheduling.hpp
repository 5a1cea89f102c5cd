#pragma once
// Real-time scheduling (SCHED_FIFO) for the threads of a live host and of its transport process.
// A process has it as root, with CAP_SYS_NICE, or up to its rtprio limit (`ulimit -r`, set in
// /etc/security/limits.conf); without it, starting or switching a thread to SCHED_FIFO fails with
// EPERM, and a library that asks for it for its own threads (CycloneDDS's receive threads) gives
// up. So a host asks first, and runs at normal priority with a warning when it may not.

#include <string>

namespace comply {

/// "" when this process may run threads SCHED_FIFO at `priority` (0 or less: asks for nothing),
/// else why not ("SCHED_FIFO priority 80: Operation not permitted"). It asks the way a thread
/// library does: it starts a thread with that scheduling, which does nothing.
std::string realtimeRefusal(int priority);

/// Makes the calling thread SCHED_FIFO at `priority` (0 or less: leaves it as it is); "" on
/// success, else why not, as realtimeRefusal() says it.
std::string makeThreadRealtime(int priority);

/// How a user is granted real-time scheduling, for a warning that it was refused.
extern const char* const kRealtimeGrantAdvice;

}  // namespace comply
