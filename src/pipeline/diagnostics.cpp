#include "comply/pipeline/diagnostics.hpp"

#include <cstdio>
#include <numeric>

namespace comply::pipeline {

std::string_view toString(WrapperState state) {
  switch (state) {
    case WrapperState::kInactive:
      return "inactive";
    case WrapperState::kActive:
      return "active";
    case WrapperState::kFault:
      return "fault";
  }
  return "unknown";
}

std::uint64_t DiagnosticsSnapshot::rejectionsTotal() const {
  return std::accumulate(rejections.begin(), rejections.end(), std::uint64_t{0});
}

void Diagnostics::setError(const char* prefix, const char* detail) noexcept {
  // Seqlock writer: odd sequence while writing; the writer is one thread at a time (the cycle, or
  // a non-RT caller while the cycle is not running).
  const std::uint32_t sequence = message_sequence_.load(std::memory_order_relaxed);
  message_sequence_.store(sequence + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  std::array<char, kMessageCapacity> text{};
  std::snprintf(text.data(), text.size(), "%s%s", prefix, detail);
  for (std::size_t i = 0; i < text.size(); ++i) {
    message_[i].store(text[i], std::memory_order_relaxed);
  }
  std::atomic_thread_fence(std::memory_order_release);
  message_sequence_.store(sequence + 2, std::memory_order_relaxed);
}

DiagnosticsSnapshot Diagnostics::snapshot() const {
  DiagnosticsSnapshot result;
  result.state = state.load();
  result.cycles = cycles.load();
  result.commands_accepted = commands_accepted.load();
  for (std::size_t i = 0; i < rejections.size(); ++i) {
    result.rejections[i] = rejections[i].load();
  }
  result.rate_limit_hits = rate_limit_hits.load();
  result.effort_limit_hits = effort_limit_hits.load();
  result.faults = faults.load();
  result.watchdog_timeouts = watchdog_timeouts.load();
  std::array<char, kMessageCapacity> copy{};
  for (;;) {
    const std::uint32_t before = message_sequence_.load(std::memory_order_acquire);
    if (before % 2 != 0) {
      continue;
    }
    for (std::size_t i = 0; i < copy.size(); ++i) {
      copy[i] = message_[i].load(std::memory_order_relaxed);
    }
    std::atomic_thread_fence(std::memory_order_acquire);
    if (message_sequence_.load(std::memory_order_relaxed) == before) {
      break;
    }
  }
  copy.back() = '\0';
  result.last_error = copy.data();
  return result;
}

}  // namespace comply::pipeline
