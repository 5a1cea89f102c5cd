// The clocks (see clock.hpp).

#include "comply/core/clock.hpp"

#include <ctime>

namespace comply {
namespace {

std::int64_t nanosecondsOf(clockid_t clock) noexcept {
  timespec now{};
  clock_gettime(clock, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

}  // namespace

std::int64_t monotonicNanoseconds() noexcept {
  return nanosecondsOf(CLOCK_MONOTONIC);
}

std::int64_t wallClockNanoseconds() noexcept {
  return nanosecondsOf(CLOCK_REALTIME);
}

}  // namespace comply
