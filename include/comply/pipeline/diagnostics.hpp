#pragma once
// Counters the real-time cycle writes and any thread reads. Writers use relaxed atomics (one
// cycle's counts need no ordering with each other); the last error text is guarded by a sequence
// counter, so the real-time side never waits for a reader.

#include <array>
#include <atomic>
#include <cstdint>
#include <string>

#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline {

enum class WrapperState : std::uint8_t { kInactive, kActive, kFault };
std::string_view toString(WrapperState state);

struct DiagnosticsSnapshot {
  WrapperState state = WrapperState::kInactive;
  std::uint64_t cycles = 0;
  std::uint64_t commands_accepted = 0;
  std::array<std::uint64_t, kRejectionReasonCount> rejections{};
  std::uint64_t rate_limit_hits = 0;    ///< joint-cycles clipped by the torque-rate limit
  std::uint64_t effort_limit_hits = 0;  ///< joint-cycles clipped by the effort limit
  std::uint64_t faults = 0;
  std::uint64_t watchdog_timeouts = 0;
  std::string last_error;

  [[nodiscard]] std::uint64_t rejectionsTotal() const;
};

class Diagnostics {
 public:
  static constexpr std::size_t kMessageCapacity = 256;

  std::atomic<WrapperState> state{WrapperState::kInactive};
  std::atomic<std::uint64_t> cycles{0};
  std::atomic<std::uint64_t> commands_accepted{0};
  std::array<std::atomic<std::uint64_t>, kRejectionReasonCount> rejections{};
  std::atomic<std::uint64_t> rate_limit_hits{0};
  std::atomic<std::uint64_t> effort_limit_hits{0};
  std::atomic<std::uint64_t> faults{0};
  std::atomic<std::uint64_t> watchdog_timeouts{0};

  /// Records the last error; callable from the real-time thread (no allocation, no lock).
  void setError(const char* prefix, const char* detail) noexcept;
  [[nodiscard]] DiagnosticsSnapshot snapshot() const;

 private:
  std::atomic<std::uint32_t> message_sequence_{0};
  std::array<std::atomic<char>, kMessageCapacity> message_{};  // atomics: race-free under TSan
};

}  // namespace comply::pipeline
