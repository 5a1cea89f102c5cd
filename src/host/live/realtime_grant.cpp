// Real-time scheduling and locked memory for `comply run`, or one warning saying why not.

#include "realtime_grant.hpp"

#include <linux/capability.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>
#include <string>

#include "comply/core/realtime_scheduling.hpp"

namespace comply::host {

namespace {

/// Whether memory mapped from now on may be locked without a limit: with a finite memlock limit,
/// MCL_FUTURE makes every later allocation, thread stack and DDS buffer past it fail (mlockall(2)),
/// the pthread_create failure of an unprivileged transport over again.
bool mayLockFuture() {
  rlimit limit{};
  if (getrlimit(RLIMIT_MEMLOCK, &limit) == 0 && limit.rlim_cur == RLIM_INFINITY) {
    return true;
  }
  return hasEffectiveCapability(CAP_IPC_LOCK);  // it lifts the limit
}

}  // namespace

bool hasEffectiveCapability(int capability) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("CapEff:", 0) == 0) {
      const unsigned long long effective = std::stoull(line.substr(7), nullptr, 16);
      return ((effective >> static_cast<unsigned>(capability)) & 1ULL) != 0;
    }
  }
  return false;
}

int grantablePriority(int asked, long long rtprio_limit, const std::function<bool(int)>& granted) {
  if (asked <= 0 || granted(asked)) {
    return std::max(asked, 0);
  }
  // A user's rtprio limit grants real-time scheduling up to it: below the asked priority, the
  // limit is still far better than none.
  if (rtprio_limit > 0 && rtprio_limit < asked && granted(static_cast<int>(rtprio_limit))) {
    return static_cast<int>(rtprio_limit);
  }
  return 0;
}

int grantRealtime(const LiveHostOptions& options, std::ostream& err) {
  std::string memory_refusal;
  // Page faults in the control loop are latency: keep everything resident when allowed. What is
  // mapped later is locked only where no limit can make the mapping fail.
  if (options.lock_memory) {
    const int flags = mayLockFuture() ? (MCL_CURRENT | MCL_FUTURE) : MCL_CURRENT;
    if (mlockall(flags) != 0) {
      memory_refusal = std::string("mlockall: ") + std::strerror(errno);
    } else if ((flags & MCL_FUTURE) == 0) {
      memory_refusal = "memory mapped after start-up is not locked (the memlock limit is finite)";
    }
  }
  int priority = options.priority;
  std::string scheduling_refusal = realtimeRefusal(priority);
  std::string clamped;
  if (!scheduling_refusal.empty()) {
    rlimit limit{};
    const long long rtprio_limit =
        getrlimit(RLIMIT_RTPRIO, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY
            ? static_cast<long long>(limit.rlim_cur)
            : 0;
    const int lowered = grantablePriority(priority, rtprio_limit, [&](int p) {
      return p == priority ? false : realtimeRefusal(p).empty();
    });
    if (lowered > 0) {
      clamped = "SCHED_FIFO priority " + std::to_string(priority) +
                " is above this user's rtprio limit (" + std::to_string(lowered) + ")";
      priority = lowered;
      scheduling_refusal.clear();
    }
  }
  if (scheduling_refusal.empty() && memory_refusal.empty() && clamped.empty()) {
    return priority;
  }
  err << "comply run: warning: ";
  if (!clamped.empty()) {
    err << clamped << ": the control, command and DDS receive threads run at priority " << priority
        << " (raise the limit, or --priority " << priority << " says so quietly)";
  }
  if (!scheduling_refusal.empty()) {
    err << "no real-time scheduling for this user (" << scheduling_refusal
        << "): the control, command and DDS receive threads run at normal priority, so other "
           "processes' load delays cycles (the lateness and overruns of the summary show it); "
           "to grant it, "
        << kRealtimeGrantAdvice << "; --priority 0 asks for none";
  }
  if (!memory_refusal.empty()) {
    err << (scheduling_refusal.empty() && clamped.empty() ? "" : ". Also ")
        << "memory is not locked (" << memory_refusal
        << "), so a page fault may delay a cycle; raise the memlock limit (`ulimit -l`; `USER - "
           "memlock unlimited` in /etc/security/limits.conf), give comply CAP_IPC_LOCK (`setcap "
           "cap_sys_nice,cap_ipc_lock+ep`) or run as root";
  }
  err << "\n";
  return scheduling_refusal.empty() ? priority : 0;
}

}  // namespace comply::host
