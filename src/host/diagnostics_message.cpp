// The live hosts' Diagnostics message (see diagnostics_message.hpp).

#include "comply/host/diagnostics_message.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "comply/host/state_sample.hpp"

namespace comply::host {
namespace {

std::vector<std::uint64_t> binsOf(
    const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins) {
  std::vector<std::uint64_t> values;
  values.reserve(bins.size());
  for (const auto& bin : bins) {
    values.push_back(bin.load(std::memory_order_relaxed));
  }
  return values;
}

}  // namespace

void LoopCounters::count(std::array<std::atomic<std::uint64_t>, kBins>& bins,
                         double seconds) noexcept {
  const double bin = seconds / kBinSeconds;
  const std::size_t index = bin <= 0.0 ? 0 : std::min(static_cast<std::size_t>(bin), kBins - 1);
  bins[index].fetch_add(1, std::memory_order_relaxed);
}

void LoopCounters::countCycle(double compute_s, bool overrun) noexcept {
  cycles.fetch_add(1, std::memory_order_relaxed);
  if (overrun) {
    overruns.fetch_add(1, std::memory_order_relaxed);
  }
  count(compute, compute_s);
}

transport::DiagnosticsMessage diagnosticsMessage(
    const pipeline::DiagnosticsSnapshot& wrapper, const LoopCounters& loop, double period_s,
    const pipeline::GateCounts& counts, std::uint64_t publisher, const std::string& host_name,
    std::vector<transport::CommandOutcomeMessage> outcomes) {
  transport::DiagnosticsMessage message;
  message.header = {transport::Stamp::now(), host_name};
  message.state = wrapper.state;
  message.cycles = loop.cycles.load(std::memory_order_relaxed);
  message.overruns = loop.overruns.load(std::memory_order_relaxed);
  message.period_s = period_s;
  message.commands_received = counts.received;
  message.commands_applied = counts.applied;
  message.commands_rejected = counts.rejected;
  message.rejections.assign(counts.per_reason.begin(), counts.per_reason.end());
  message.watchdog_timeouts = wrapper.watchdog_timeouts;
  message.faults = wrapper.faults;
  message.rate_limit_hits = wrapper.rate_limit_hits;
  message.effort_limit_hits = wrapper.effort_limit_hits;
  message.governor_hits = wrapper.governor_hits;
  message.wall_reference_hits = wrapper.wall_reference_hits;
  message.wall_brake_hits = wrapper.wall_brake_hits;
  message.reflex_trips = wrapper.reflex_trips;
  message.contact_speed_hits = wrapper.contact_speed_hits;
  message.histogram_bin_s = LoopCounters::kBinSeconds;
  message.compute_time_histogram = binsOf(loop.compute);
  message.start_lateness_histogram = binsOf(loop.lateness);
  message.last_fault = wrapper.last_fault;
  // The gate's: every command passes it, the ones it refuses itself (stamp, publisher) too.
  message.last_rejection = counts.last_rejection;
  if (publisher != 0) {
    std::ostringstream text;
    text << std::hex << publisher;
    message.publisher = text.str();
  }
  message.outcomes = std::move(outcomes);
  return message;
}

}  // namespace comply::host
