#pragma once
// A channel's rate limit: at most `rate_hz` messages a second on average. Each message let
// through moves the next slot a period after the last slot, not after the message, so that a
// publisher's jitter (a message a little early, the next a little late) does not thin the rate;
// but at least half a period after the message, so that a quiet stretch is not caught up in a
// burst.

#include <algorithm>
#include <chrono>

namespace comply::viewer {

class RateLimit {
 public:
  using Clock = std::chrono::steady_clock;

  /// `rate_hz` <= 0: no limit.
  explicit RateLimit(double rate_hz = 0.0)
      : period_(rate_hz > 0.0 ? std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(1.0 / rate_hz))
                              : Clock::duration::zero()) {}

  [[nodiscard]] bool allows(Clock::time_point now) const noexcept {
    return period_ == Clock::duration::zero() || now >= next_slot_;
  }
  /// A message let through at `now`.
  void take(Clock::time_point now) noexcept {
    if (period_ != Clock::duration::zero()) {
      next_slot_ = std::max(next_slot_ + period_, now + period_ / 2);
    }
  }

 private:
  Clock::duration period_;
  Clock::time_point next_slot_{};
};

}  // namespace comply::viewer
