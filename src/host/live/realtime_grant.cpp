// Real-time scheduling and locked memory for `comply run`, or one warning saying why not.

#include "realtime_grant.hpp"

#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <ostream>
#include <string>

#include "comply/core/realtime_scheduling.hpp"

namespace comply::host {

int grantRealtime(const LiveHostOptions& options, std::ostream& err) {
  std::string memory_refusal;
  // Page faults in the control loop are latency: keep everything resident when allowed.
  if (options.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    memory_refusal = std::string("mlockall: ") + std::strerror(errno);
  }
  const std::string scheduling_refusal = realtimeRefusal(options.priority);
  if (scheduling_refusal.empty() && memory_refusal.empty()) {
    return options.priority;
  }
  err << "comply run: warning: ";
  if (!scheduling_refusal.empty()) {
    err << "no real-time scheduling for this user (" << scheduling_refusal
        << "): the control, command and DDS receive threads run at normal priority, so other "
           "processes' load delays cycles (the lateness and overruns of the summary show it); "
           "to grant it, "
        << kRealtimeGrantAdvice << "; --priority 0 asks for none";
  }
  if (!memory_refusal.empty()) {
    err << (scheduling_refusal.empty() ? "" : ". Also ") << "memory is not locked ("
        << memory_refusal
        << "), so a page fault may delay a cycle; raise the memlock limit (`ulimit -l`; `USER - "
           "memlock unlimited` in /etc/security/limits.conf) or run as root";
  }
  err << "\n";
  return scheduling_refusal.empty() ? options.priority : 0;
}

}  // namespace comply::host
