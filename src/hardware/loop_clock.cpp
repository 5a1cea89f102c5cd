#include "comply/hardware/loop_clock.hpp"

#include <cerrno>
#include <cmath>
#include <ctime>

#include "comply/core/clock.hpp"

namespace comply::hardware {
double monotonicSeconds() noexcept {
  return 1e-9 * static_cast<double>(monotonicNanoseconds());
}

WallClock::WallClock() : origin_s_(monotonicSeconds()) {}

double WallClock::now() noexcept {
  return monotonicSeconds() - origin_s_;
}

void WallClock::waitUntil(double time_s) noexcept {
  // An absolute deadline: a late wake-up does not push every later cycle back.
  const double deadline = origin_s_ + time_s;
  timespec target{};
  target.tv_sec = static_cast<time_t>(std::floor(deadline));
  target.tv_nsec = static_cast<long>((deadline - std::floor(deadline)) * 1e9);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &target, nullptr) == EINTR) {
  }
}

}  // namespace comply::hardware
