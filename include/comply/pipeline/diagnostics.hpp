#pragma once
// Counters the real-time cycle writes and any thread reads. Writers use relaxed atomics (one
// cycle's counts need no ordering with each other). The last fault (written by the cycle) and the
// last rejection (written by the intake) each have their own text slot guarded by a sequence
// counter: every slot has exactly one writer, so the real-time side never waits for anyone and a
// reader never sees a torn text.

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>

#include "comply/core/wrapper_state.hpp"
#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline {

using comply::WrapperState;

/// The gain guard's account (passivity.* options: the energy tank), as of the last cycle. Totals
/// count from activation. Every field is 0 (and gain_fraction 1) while the tank is off.
struct PassivitySnapshot {
  bool enabled = false;                  ///< passivity.enabled
  double tank_energy_j = 0.0;            ///< [J] task account (Cartesian or joint stiffness)
  double nullspace_tank_energy_j = 0.0;  ///< [J] nullspace account (Cartesian control)
  double injected_j = 0.0;               ///< [J] total paid for stiffness and task-frame changes
  double dissipated_j = 0.0;             ///< [J] total credited from the damping (a lower bound)
  double refused_j = 0.0;      ///< [J] what the change held back this cycle would have injected
  double gain_fraction = 1.0;  ///< [-] fraction of the commanded stiffness change in force
};

struct DiagnosticsSnapshot {
  WrapperState state = WrapperState::kInactive;
  std::uint64_t cycles = 0;
  std::uint64_t commands_accepted = 0;
  std::array<std::uint64_t, kRejectionReasonCount> rejections{};
  std::uint64_t rate_limit_hits = 0;      ///< joint-cycles clipped by the torque-rate limit
  std::uint64_t effort_limit_hits = 0;    ///< joint-cycles clipped by the effort limit
  std::uint64_t governor_hits = 0;        ///< cycles the motion governor acted in
  std::uint64_t wall_reference_hits = 0;  ///< cycles the walls moved the law's reference
  std::uint64_t wall_brake_hits = 0;      ///< cycles the walls' barrier braked the TCP
  std::uint64_t reflex_trips = 0;         ///< times the contact reflex tripped (any reaction)
  bool reflex_latched = false;            ///< its hold (or retreat) waits for a reset
  std::uint64_t contact_speed_hits = 0;   ///< cycles the contact-speed stage acted in
  std::uint64_t faults = 0;
  std::uint64_t watchdog_timeouts = 0;
  PassivitySnapshot passivity;
  std::string last_fault;      ///< why the controller last entered FAULT ("" if never)
  std::string last_rejection;  ///< why the last rejected command was rejected ("" if none)
  std::string last_error;      ///< the newer of the two

  [[nodiscard]] std::uint64_t rejectionsTotal() const;
};

/// One text written by one thread, read by any: a sequence lock over atomic characters.
class MessageSlot {
 public:
  static constexpr std::size_t kCapacity = 256;
  /// Single writer; no allocation, no lock. `order` ranks this text against other slots.
  void write(const char* prefix, const char* detail, std::uint64_t order) noexcept;
  /// The text and its order (0: never written).
  [[nodiscard]] std::pair<std::string, std::uint64_t> read() const;

 private:
  std::atomic<std::uint32_t> sequence_{0};
  std::atomic<std::uint64_t> order_{0};
  std::array<std::atomic<char>, kCapacity> text_{};  // atomics: race-free under TSan
};

class Diagnostics {
 public:
  std::atomic<WrapperState> state{WrapperState::kInactive};
  std::atomic<std::uint64_t> cycles{0};
  std::atomic<std::uint64_t> commands_accepted{0};
  std::array<std::atomic<std::uint64_t>, kRejectionReasonCount> rejections{};
  std::atomic<std::uint64_t> rate_limit_hits{0};
  std::atomic<std::uint64_t> effort_limit_hits{0};
  std::atomic<std::uint64_t> governor_hits{0};
  std::atomic<std::uint64_t> wall_reference_hits{0};
  std::atomic<std::uint64_t> wall_brake_hits{0};
  std::atomic<std::uint64_t> reflex_trips{0};
  /// The contact reflex holds and refuses commands until a reset (the intake reads it).
  std::atomic<bool> reflex_latched{false};
  std::atomic<std::uint64_t> contact_speed_hits{0};
  std::atomic<std::uint64_t> faults{0};
  std::atomic<std::uint64_t> watchdog_timeouts{0};
  /// The gain guard's account, written by the cycle (see PassivitySnapshot).
  std::atomic<bool> passivity_enabled{false};
  std::atomic<double> tank_energy_j{0.0};
  std::atomic<double> nullspace_tank_energy_j{0.0};
  std::atomic<double> injected_j{0.0};
  std::atomic<double> dissipated_j{0.0};
  std::atomic<double> refused_j{0.0};
  std::atomic<double> gain_fraction{1.0};

  /// The cycle's side (or the lifecycle's, between cycles): why FAULT was entered.
  void setFault(const char* prefix, const char* detail) noexcept;
  /// The intake's side (one sender at a time): why a command was rejected.
  void setRejection(const char* prefix, const char* detail) noexcept;
  [[nodiscard]] DiagnosticsSnapshot snapshot() const;
  /// The gain guard's account alone: no allocation, so the real-time thread may read it too.
  [[nodiscard]] PassivitySnapshot passivity() const noexcept;

 private:
  std::atomic<std::uint64_t> events_{0};
  MessageSlot fault_;
  MessageSlot rejection_;
};

}  // namespace comply::pipeline
