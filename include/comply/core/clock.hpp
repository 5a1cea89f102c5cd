#pragma once
// The two clocks every part of comply reads: CLOCK_MONOTONIC for durations and deadlines (loop
// timing, the publisher rule) and CLOCK_REALTIME for stamps, as ROS time is.

#include <cstdint>

namespace comply {

/// CLOCK_MONOTONIC [ns].
std::int64_t monotonicNanoseconds() noexcept;
/// CLOCK_REALTIME [ns since the epoch].
std::int64_t wallClockNanoseconds() noexcept;

}  // namespace comply
