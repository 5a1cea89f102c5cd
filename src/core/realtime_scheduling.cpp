// Real-time scheduling and whether this process may have it (see realtime_scheduling.hpp).

#include "comply/core/realtime_scheduling.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace comply {
namespace {

std::string refusal(int priority, int error) {
  return "SCHED_FIFO priority " + std::to_string(priority) + ": " + std::strerror(error);
}

extern "C" void* doNothing(void* /*argument*/) {
  return nullptr;
}

}  // namespace

const char* const kRealtimeGrantAdvice =
    "run as root, or raise the user's rtprio limit (`ulimit -r` shows it; a line `USER - rtprio "
    "99` in /etc/security/limits.conf sets it at the next login), or give the programs "
    "CAP_SYS_NICE (`setcap cap_sys_nice+ep` on comply and comply-transport)";

std::string realtimeRefusal(int priority) {
  if (priority <= 0) {
    return {};
  }
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  sched_param parameters{};
  parameters.sched_priority = priority;
  int error = pthread_attr_setinheritsched(&attributes, PTHREAD_EXPLICIT_SCHED);
  if (error == 0) {
    error = pthread_attr_setschedpolicy(&attributes, SCHED_FIFO);
  }
  if (error == 0) {
    error = pthread_attr_setschedparam(&attributes, &parameters);
  }
  pthread_t thread{};
  if (error == 0) {
    error = pthread_create(&thread, &attributes, doNothing, nullptr);
  }
  if (error == 0) {
    pthread_join(thread, nullptr);
  }
  pthread_attr_destroy(&attributes);
  return error == 0 ? std::string() : refusal(priority, error);
}

std::string makeThreadRealtime(int priority) {
  if (priority <= 0) {
    return {};
  }
  sched_param parameters{};
  parameters.sched_priority = priority;
  const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &parameters);
  return error == 0 ? std::string() : refusal(priority, error);
}

}  // namespace comply
