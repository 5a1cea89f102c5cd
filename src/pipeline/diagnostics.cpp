#include "comply/pipeline/diagnostics.hpp"

#include <cstdio>
#include <numeric>

namespace comply::pipeline {

std::uint64_t DiagnosticsSnapshot::rejectionsTotal() const {
  return std::accumulate(rejections.begin(), rejections.end(), std::uint64_t{0});
}

void MessageSlot::write(const char* prefix, const char* detail, std::uint64_t order) noexcept {
  const std::uint32_t sequence = sequence_.load(std::memory_order_relaxed);
  sequence_.store(sequence + 1, std::memory_order_relaxed);  // odd: being written
  std::atomic_thread_fence(std::memory_order_release);
  std::array<char, kCapacity> text{};
  std::snprintf(text.data(), text.size(), "%s%s", prefix, detail);
  for (std::size_t i = 0; i < text.size(); ++i) {
    text_[i].store(text[i], std::memory_order_relaxed);
  }
  order_.store(order, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  sequence_.store(sequence + 2, std::memory_order_relaxed);
}

std::pair<std::string, std::uint64_t> MessageSlot::read() const {
  std::array<char, kCapacity> copy{};
  std::uint64_t order = 0;
  for (;;) {
    const std::uint32_t before = sequence_.load(std::memory_order_acquire);
    if (before % 2 != 0) {
      continue;  // the one writer is mid-write; it never waits, so this ends
    }
    for (std::size_t i = 0; i < copy.size(); ++i) {
      copy[i] = text_[i].load(std::memory_order_relaxed);
    }
    order = order_.load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (sequence_.load(std::memory_order_relaxed) == before) {
      break;
    }
  }
  copy.back() = '\0';
  return {copy.data(), order};
}

void Diagnostics::setFault(const char* prefix, const char* detail) noexcept {
  fault_.write(prefix, detail, events_.fetch_add(1, std::memory_order_relaxed) + 1);
}

void Diagnostics::setRejection(const char* prefix, const char* detail) noexcept {
  rejection_.write(prefix, detail, events_.fetch_add(1, std::memory_order_relaxed) + 1);
}

PassivitySnapshot Diagnostics::passivity() const noexcept {
  PassivitySnapshot result;
  result.enabled = passivity_enabled.load(std::memory_order_relaxed);
  result.tank_energy_j = tank_energy_j.load(std::memory_order_relaxed);
  result.nullspace_tank_energy_j = nullspace_tank_energy_j.load(std::memory_order_relaxed);
  result.injected_j = injected_j.load(std::memory_order_relaxed);
  result.dissipated_j = dissipated_j.load(std::memory_order_relaxed);
  result.refused_j = refused_j.load(std::memory_order_relaxed);
  result.gain_fraction = gain_fraction.load(std::memory_order_relaxed);
  return result;
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
  result.governor_hits = governor_hits.load();
  result.wall_reference_hits = wall_reference_hits.load();
  result.wall_brake_hits = wall_brake_hits.load();
  result.reflex_trips = reflex_trips.load();
  result.reflex_latched = reflex_latched.load();
  result.contact_speed_hits = contact_speed_hits.load();
  result.faults = faults.load();
  result.watchdog_timeouts = watchdog_timeouts.load();
  result.passivity = passivity();
  auto [fault, fault_order] = fault_.read();
  auto [rejection, rejection_order] = rejection_.read();
  result.last_error = fault_order >= rejection_order ? fault : rejection;
  result.last_fault = std::move(fault);
  result.last_rejection = std::move(rejection);
  return result;
}

}  // namespace comply::pipeline
