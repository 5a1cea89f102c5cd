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
// between the two (position, velocity and acceleration at the start) decays along a quintic to
// zero, so the reference has no jump in position, velocity or acceleration; the gains, the task
// frame and the feedforward fade from their values in force to the chunk's along the same curve.
//
// Threads. load() on the intake thread (one producer at a time) writes into a free slot; start(),
// play() and stop() on the real-time thread. A slot is free again when the cycle has finished with
// it. No allocation after construction, no locks.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>

#include "comply/core/chunk.hpp"
#include "comply/pipeline/command_bus_variant.hpp"

namespace comply::pipeline {

class ChunkPlayer {
 public:
  /// Slots: one playing, one or two waiting in the intake queue, one being written.
  static constexpr int kSlots = 4;

  /// `command_kind`: COMPLY_COMMAND_*; `blend_time_s` >= 0 (0: the chunk starts at once).
  ChunkPlayer(int command_kind, int dof, double blend_time_s);
  ~ChunkPlayer();
  ChunkPlayer(const ChunkPlayer&) = delete;
  ChunkPlayer& operator=(const ChunkPlayer&) = delete;

  // ---- intake (non-real-time) ------------------------------------------------------------------
  /// Copies a validated chunk into a free slot, its times moved onto the controller's clock by
  /// `host_to_controller_s` (controller time = host time + it), and derives the waypoint
  /// velocities; `sequence` is its number (CommandId), for dropWaiting(). Returns the slot, or -1
  /// when every slot is in use (the sender is too fast).
  int load(const CartesianChunk& chunk, double host_to_controller_s, std::uint64_t sequence = 0);
  int load(const JointChunk& chunk, double host_to_controller_s, std::uint64_t sequence = 0);
  /// A loaded slot that will never be started (its intake message was refused or dropped).
  void release(int slot) noexcept;

  // ---- real-time --------------------------------------------------------------------------------
  /// Starts the chunk in `slot` at controller time `now_s`, blending in from `in_force` (the
  /// reference of this same cycle). The chunk played before it, if any, is released.
  void start(int slot, const CommandBus& in_force, double now_s) noexcept;
  /// Writes the running chunk's reference at `now_s` into `active` (position, velocity,
  /// acceleration and the groups the chunk drives). Returns false once the chunk has ended (past
  /// its last waypoint and its blend): it is then released and `active` holds the last waypoint
  /// at rest.
  bool play(double now_s, CommandBus& active) noexcept;
  /// Releases the running chunk; `active` keeps what play() last wrote.
  void stop() noexcept;
  /// Stops the running chunk if it is numbered `sequence` (0: whichever) and its first waypoint
  /// is still ahead of `now_s`: a chunk waiting for its start whose sender left, or on a reset.
  /// True when it stopped one.
  bool dropWaiting(std::uint64_t sequence, double now_s) noexcept;

  [[nodiscard]] bool playing() const noexcept { return playing_ >= 0; }
  /// The groups the running chunk drives (COMPLY_FIELD_*), 0 when none plays.
  [[nodiscard]] std::uint32_t fields() const noexcept;
  /// The stamp [s] of the running chunk.
  [[nodiscard]] double stamp() const noexcept;

  struct Slots;  // chunk_player.cpp

 private:
  std::unique_ptr<Slots> slots_;
  int playing_ = -1;
};

}  // namespace comply::pipeline
