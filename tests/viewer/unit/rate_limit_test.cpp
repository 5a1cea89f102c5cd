// A channel's rate limit on a clock of the test's own.

#include "comply/viewer/rate_limit.hpp"

#include <gtest/gtest.h>

namespace comply::viewer {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

/// Offers messages at `offsets` (from a start) to a limit of `rate_hz`; how many it lets through.
int letThrough(double rate_hz, const std::vector<microseconds>& offsets) {
  RateLimit limit(rate_hz);
  const RateLimit::Clock::time_point start{std::chrono::hours(1)};
  int passed = 0;
  for (const microseconds offset : offsets) {
    if (limit.allows(start + offset)) {
      limit.take(start + offset);
      ++passed;
    }
  }
  return passed;
}

TEST(RateLimit, JitterAroundTheRateKeepsTheRate) {
  // Every 0.7 ms and 1.3 ms in turn, a mean of 1 ms, to a 1 kHz limit: a limit counted from
  // each message would refuse every message 0.7 ms after the one before, half of them.
  std::vector<microseconds> offsets;
  microseconds t{0};
  for (int i = 0; i < 1000; ++i) {
    t += microseconds(i % 2 == 0 ? 700 : 1300);
    offsets.push_back(t);
  }
  EXPECT_EQ(letThrough(1000.0, offsets), 1000);
}

TEST(RateLimit, FasterMessagesAreThinnedToTheRate) {
  std::vector<microseconds> offsets;
  for (int i = 0; i < 10000; ++i) {
    offsets.push_back(microseconds(100 * i));  // 10 kHz for 1 s
  }
  const int passed = letThrough(1000.0, offsets);
  EXPECT_GE(passed, 999);
  EXPECT_LE(passed, 1001);
}

TEST(RateLimit, AQuietStretchIsNotCaughtUpInABurst) {
  // One message, a second of nothing, then messages back to back: one goes, then the rate.
  std::vector<microseconds> offsets{microseconds(0)};
  for (int i = 0; i < 100; ++i) {
    offsets.push_back(milliseconds(1000) + microseconds(10 * i));  // 1 ms of them
  }
  EXPECT_EQ(letThrough(100.0, offsets), 2);
}

TEST(RateLimit, NoRateLetsEverythingThrough) {
  EXPECT_EQ(letThrough(0.0, {microseconds(0), microseconds(0), microseconds(1)}), 3);
}

}  // namespace
}  // namespace comply::viewer
