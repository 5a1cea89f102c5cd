#pragma once
// The chunk player: holds the timed chunks the intake loaded and, on the real-time thread, writes
// the running chunk's reference into the command in force every cycle (docs/chunks.md).
//
// Curve. Positions (TCP or joints) follow a cubic Hermite spline through the waypoints, C1: the
// velocity at a waypoint is the one the chunk gives (kVelocity) or else implied, the
// interval-weighted mean of the two neighbouring secants, the secant at the first waypoint, and
// zero at the last, so a chunk comes to rest at its end and holds its last waypoint after it.
// Before the first waypoint the curve comes from rest: one segment earlier, half that segment's
// travel behind, it accelerates evenly into the first waypoint's velocity (and holds that lead-in
// point before). Orientations follow the same spline on SO(3), in the rotation vector of each
// segment relative to its first waypoint, with the end slopes mapped through the right Jacobian,
// so the angular velocity is continuous too. Gains, feedforward and nullspace move linearly
// between waypoints (a convex combination: symmetric positive semi-definite blocks stay so), the
// task frame by spherical interpolation.
//
// Preemption. A chunk starts from the reference in force: over `blend_time_s` the difference
// between the two (position and velocity at the start) decays along a quintic to zero, so the
// reference has no jump in position or velocity (its acceleration steps, as at any waypoint of
// the C1 curve); the gains, the task frame and the feedforward fade from their values in force to
// the chunk's along the same curve.
//
// Takeover. A chunk may name the time it takes over (RTC's frozen prefix: "keep the running
// chunk's first actions, replace the rest"): it waits until the first cycle at or after that time
// (a nanosecond's tolerance) while the running chunk plays on (or, with none playing, the
// reference in force holds), and starts at that time itself, from the running chunk's reference
// then; its waypoint at that time takes that reference's velocity (load()'s `joins`). A chunk
// that keeps the committed prefix thus continues the curve in force exactly. A newer chunk
// supersedes one still waiting.
//
// Prediction. predict() evaluates off the cycle what the cycle will write at given times if no
// new chunk arrives, with the same code on the same data: the running chunk's start (published by
// the cycle whenever it changes) and its slot, which no load() overwrites while the intake's lock
// is held.
//
// Threads. load() and predict() on the intake thread (one at a time, under the intake's lock)
// write into a free slot or read; start(), play() and stop() on the real-time thread. A slot is
// free again when the cycle has finished with it. No allocation after construction, no locks.

#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>

#include "comply/core/chunk.hpp"
#include "comply/pipeline/chunk_timing.hpp"
#include "comply/pipeline/command_bus_variant.hpp"

namespace comply::pipeline {

class ChunkPlayer {
 public:
  /// Slots: one playing, one waiting for its takeover, one or two waiting in the intake queue,
  /// one being written.
  static constexpr int kSlots = 5;
  /// Timing records one cycle can produce: a waiting chunk superseded or dropped, and one taking
  /// over (twice: the waiting one at its time, then a newer one at once).
  static constexpr int kEventsPerCycle = 4;
  /// A takeover time is met by the first cycle no more than this before it [s]: chunk times that
  /// are cycle times up to rounding take over in that cycle, not the next.
  static constexpr double kTakeoverTolerance_s = 1e-9;

  /// `command_kind`: COMPLY_COMMAND_*; `blend_time_s` >= 0 (0: the chunk starts at once).
  ChunkPlayer(int command_kind, int dof, double blend_time_s);
  ~ChunkPlayer();
  ChunkPlayer(const ChunkPlayer&) = delete;
  ChunkPlayer& operator=(const ChunkPlayer&) = delete;

  // ---- intake (non-real-time, under the intake's lock) ---------------------------------------
  /// Copies a validated chunk into a free slot, its times (waypoints, observation, takeover)
  /// moved onto the controller's clock by `host_to_controller_s` (controller time = host time +
  /// it), and derives the waypoint velocities; `sequence` is its number (CommandId), for
  /// dropWaiting() and its timing record; `received_s`: when the intake accepted it, on the
  /// controller's clock; `joins`: for a chunk that waits for its takeover, the reference the
  /// cycle will write then (the intake's prediction), whose velocity the waypoint at that time
  /// takes unless the chunk gives velocities (a C1 join). Returns the slot, or -1 when every
  /// slot is in use (the sender is too fast).
  int load(const CartesianChunk& chunk, double host_to_controller_s, std::uint64_t sequence = 0,
           double received_s = ChunkTiming::kNone, const CommandBus* joins = nullptr);
  int load(const JointChunk& chunk, double host_to_controller_s, std::uint64_t sequence = 0,
           double received_s = ChunkTiming::kNone, const CommandBus* joins = nullptr);
  /// A loaded slot that will never be started (its intake message was refused or dropped).
  void release(int slot) noexcept;

  /// The reference the cycle will write at each of `times_s` (controller clock, increasing) if no
  /// new chunk arrives: `out[k]` holds the command in force on entry (the groups no chunk drives
  /// keep it) and the running chunk's reference at that time on return, or the waiting chunk's
  /// once it takes over, in the cycle of the grid `last_cycle_s` + j `period_s` (j >= 1) where
  /// the cycle takes it over. A time before the running chunk started is answered from the chunk
  /// before it while its slot still holds it; otherwise that entry's position is NaN and the
  /// return is false. Allocation-free; the intake's thread (not the cycle's).
  bool predict(std::span<const double> times_s, double last_cycle_s, double period_s,
               std::span<CommandBus> out);

  // ---- real-time --------------------------------------------------------------------------------
  /// Takes the chunk in `slot` in the cycle at `now_s`: it starts now, blending in from
  /// `in_force` (the reference of this same cycle), or, when it names a takeover still ahead,
  /// waits for it (a chunk already waiting is superseded). The chunk played before, if any, is
  /// released. Returns true when it started.
  bool take(int slot, const CommandBus& in_force, double now_s) noexcept;
  /// A waiting chunk whose takeover time has come starts now: `active` must hold the reference
  /// of this cycle so far (the running chunk's is written first). Returns its number, 0 when none
  /// started.
  std::uint64_t takeOverDue(double now_s, CommandBus& active) noexcept;
  /// Writes the running chunk's reference at `now_s` into `active` (position, velocity,
  /// acceleration and the groups the chunk drives). Returns false once the chunk has ended (past
  /// its last waypoint and its blend): it is then released and `active` holds the last waypoint
  /// at rest.
  bool play(double now_s, CommandBus& active) noexcept;
  /// Releases the running chunk and a waiting one (recorded as dropped); `active` keeps what
  /// play() last wrote.
  void stop() noexcept;
  /// Stops the running chunk if it is numbered `sequence` (0: whichever) and its first waypoint
  /// is still ahead of `now_s`, and drops a waiting chunk so numbered: a chunk waiting for its
  /// start whose sender left, or on a reset. True when it stopped the running one.
  bool dropWaiting(std::uint64_t sequence, double now_s) noexcept;

  /// The timing records of the chunks that took over, were superseded or dropped since the last
  /// clearEvents() (the cycle clears them as it starts).
  [[nodiscard]] std::span<const ChunkTiming> events() const noexcept {
    return {events_.data(), static_cast<std::size_t>(event_count_)};
  }
  void clearEvents() noexcept { event_count_ = 0; }

  [[nodiscard]] bool playing() const noexcept { return playing_ >= 0; }
  [[nodiscard]] bool waiting() const noexcept { return waiting_ >= 0; }
  /// The groups the running chunk drives and those the waiting one will (COMPLY_FIELD_*), 0 when
  /// none.
  [[nodiscard]] std::uint32_t fields() const noexcept;
  /// The stamp [s] of the running chunk.
  [[nodiscard]] double stamp() const noexcept;

  struct Slots;  // chunk_player.cpp

 private:
  void begin(int slot, const CommandBus& in_force, double now_s) noexcept;
  void endWaiting(ChunkEnd end) noexcept;
  void publish() noexcept;
  ChunkTiming* newEvent() noexcept;

  std::unique_ptr<Slots> slots_;
  int playing_ = -1;
  int waiting_ = -1;
  /// When the last chunk ran out (controller time), NaN when none did or a command ended it.
  double ran_out_s_ = std::numeric_limits<double>::quiet_NaN();
  double last_play_s_ = 0.0;  ///< the time play() last wrote at (controller clock)
  std::array<ChunkTiming, kEventsPerCycle> events_{};
  int event_count_ = 0;
};

}  // namespace comply::pipeline
