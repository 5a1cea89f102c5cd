#pragma once
// The Diagnostics message of a live host (`comply run`, or any host built on this library): the
// loop's timing, written lock-free by the control thread (LoopCounters), the wrapper's counters
// and the command gate's accounting, built off the control thread. The state's message is
// state_sample.hpp's.

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

/// Cycle timing, written by the control thread, read by anyone.
struct LoopCounters {
  static constexpr std::size_t kBins = 200;
  static constexpr double kBinSeconds = 10e-6;  ///< 10 us bins: 0..2 ms, the last one open
  std::atomic<std::uint64_t> cycles{0};
  std::atomic<std::uint64_t> overruns{0};
  std::atomic<std::uint64_t> applied_deferred{0};  ///< applied events the gate had no room for yet
  /// Chunk timing records the gate had no room for (their outcomes and the recording go without).
  std::atomic<std::uint64_t> chunk_timings_lost{0};
  std::array<std::atomic<std::uint64_t>, kBins> compute{};
  std::array<std::atomic<std::uint64_t>, kBins> lateness{};

  /// Counts `seconds` in `bins`: wait-free, for the control thread.
  static void count(std::array<std::atomic<std::uint64_t>, kBins>& bins, double seconds) noexcept;
  /// One cycle that took `compute_s` of computing, an overrun or not: wait-free.
  void countCycle(double compute_s, bool overrun) noexcept;
};

/// The counters of the wrapper, the loop and the gate, with `outcomes` attached; header.frame_id
/// is `host_name`, header.stamp the wall clock; last_rejection the gate's (allocates: off the
/// control thread).
transport::DiagnosticsMessage diagnosticsMessage(
    const pipeline::DiagnosticsSnapshot& wrapper, const LoopCounters& loop, double period_s,
    const pipeline::GateCounts& counts, std::uint64_t publisher, const std::string& host_name,
    std::vector<transport::CommandOutcomeMessage> outcomes);

}  // namespace comply::host
