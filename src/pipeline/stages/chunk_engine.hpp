#pragma once
// The chunk player's state (chunk_player.hpp has the rules): its slots, how the running chunk
// started, the view predict() reads, and the evaluation the cycle and predict() share. Private to
// chunk_player.cpp and chunk_prediction.cpp.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>

#include "chunk_blend.hpp"
#include "chunk_curve.hpp"
#include "chunk_track.hpp"
#include "comply/core/rotation.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/pipeline/chunk_player.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace chunk {

inline constexpr std::uint8_t kFree = 0;
inline constexpr std::uint8_t kLoaded = 1;

/// Fades the groups `fields` of `chunk` in from `from` (fraction 0: all `from`, 1: all chunk)
/// into `active`.
inline void fadeSettings(const Cartesian& from, const Cartesian& chunk, std::uint32_t fields,
                         double fraction, Cartesian& active) noexcept {
  const int dof = active.dof;
  if ((fields & COMPLY_FIELD_STIFFNESS) != 0) {
    lerp(from.stiffness_translational, chunk.stiffness_translational, fraction, 9,
         active.stiffness_translational);
    lerp(from.stiffness_rotational, chunk.stiffness_rotational, fraction, 9,
         active.stiffness_rotational);
  }
  if ((fields & COMPLY_FIELD_DAMPING) != 0) {
    // Blocks of two modes mean different things: a change of mode takes effect at once.
    const double f = from.damping_mode == chunk.damping_mode ? fraction : 1.0;
    lerp(from.damping_translational, chunk.damping_translational, f, 9,
         active.damping_translational);
    lerp(from.damping_rotational, chunk.damping_rotational, f, 9, active.damping_rotational);
    lerp(from.damping_ratio, chunk.damping_ratio, f, 6, active.damping_ratio);
    active.damping_mode = chunk.damping_mode;
  }
  if ((fields & COMPLY_FIELD_TASK_FRAME) != 0) {
    toXyzw(slerpShort(fromXyzw(from.task_frame), fromXyzw(chunk.task_frame), fraction),
           active.task_frame);
  }
  if ((fields & COMPLY_FIELD_WRENCH_FEEDFORWARD) != 0) {
    lerp(from.wrench_feedforward, chunk.wrench_feedforward, fraction, 6, active.wrench_feedforward);
  }
  if ((fields & COMPLY_FIELD_TORQUE_FEEDFORWARD) != 0) {
    lerp(from.torque_feedforward, chunk.torque_feedforward, fraction, dof,
         active.torque_feedforward);
  }
  if ((fields & COMPLY_FIELD_NULLSPACE) != 0) {
    lerp(from.nullspace_position, chunk.nullspace_position, fraction, dof,
         active.nullspace_position);
    lerp(from.nullspace_stiffness, chunk.nullspace_stiffness, fraction, dof,
         active.nullspace_stiffness);
    lerp(from.nullspace_damping, chunk.nullspace_damping, fraction, dof, active.nullspace_damping);
  }
}

inline void fadeSettings(const Joint& from, const Joint& chunk, std::uint32_t fields,
                         double fraction, Joint& active) noexcept {
  if ((fields & COMPLY_FIELD_STIFFNESS) != 0) {
    lerp(from.stiffness, chunk.stiffness, fraction, active.dof, active.stiffness);
  }
  if ((fields & COMPLY_FIELD_DAMPING) != 0) {
    lerp(from.damping, chunk.damping, fraction, active.dof, active.damping);
  }
  if ((fields & COMPLY_FIELD_TORQUE_FEEDFORWARD) != 0) {
    lerp(from.torque_feedforward, chunk.torque_feedforward, fraction, active.dof,
         active.torque_feedforward);
  }
}

inline void writeMotion(const CartesianMotion& m, Cartesian& to) noexcept {
  Vector3Map(to.position) = m.position;
  toXyzw(m.orientation, to.orientation);
  Eigen::Map<Vector6d>(to.twist) << m.velocity, m.angular_velocity;
  Eigen::Map<Vector6d>(to.acceleration) << m.acceleration, m.angular_acceleration;
}

inline void writeMotion(const JointMotion& m, Joint& to) noexcept {
  const int dof = to.dof;
  std::copy_n(m.position.data(), dof, to.position);
  std::copy_n(m.velocity.data(), dof, to.velocity);
  std::copy_n(m.acceleration.data(), dof, to.acceleration);
}

/// How the running chunk started: what the cycle and predict() evaluate it from.
/// How the running chunk started: what the cycle and predict() evaluate it from.
template <typename Bus>
struct Start {
  std::uint64_t sequence = 0;  ///< 0: no chunk
  int slot = -1;
  Bus from{};  ///< the reference in force when it started
  OffsetOf<Bus> offset{};
  double start_s = 0.0;
};

/// What predict() reads of the cycle's player, published whenever it changes.
template <typename Bus>
struct View {
  Start<Bus> running;  ///< sequence 0: none plays
  /// The chunk that played before (sequence 0: none), until `previous_end_s`: taken over, run out
  /// or stopped.
  Start<Bus> previous;
  double previous_end_s = 0.0;
  int waiting_slot = -1;
  std::uint64_t waiting_sequence = 0;
};

/// The typed half of the player: its slots and the running chunk's blend.
template <typename Bus>
struct Engine {
  std::array<Track<Bus>, ChunkPlayer::kSlots> tracks;
  Start<Bus> running;
  Start<Bus> previous;
  double previous_end_s = 0.0;
  int cursor = 0;
  Bus settings{};  // scratch: the chunk's settings at this cycle's place
  TripleBuffer<View<Bus>> view;
  // predict()'s own, so that it allocates nothing.
  Bus predicted_settings{};
  Start<Bus> predicted_start;
};

template <typename Bus>
Start<Bus> startOf(const Track<Bus>& track, int slot, const Bus& in_force, double now_s) noexcept {
  Start<Bus> start;
  start.sequence = track.sequence == 0 ? 1 : track.sequence;  // 0 means none
  start.slot = slot;
  start.from = in_force;
  start.start_s = now_s;
  int cursor = 0;
  start.offset = offsetAt(in_force, motionAt(track, placeOf(track, now_s, cursor)));
  return start;
}

/// The running chunk's reference at `now_s` into `active`; returns whether the chunk still runs
/// after it. The cycle's play() and predict() both evaluate it here.
template <typename Bus>
bool evaluate(const Track<Bus>& track, const Start<Bus>& start, double blend_time_s, double now_s,
              int& cursor, Bus& settings_scratch, Bus& active) noexcept {
  const Place place = placeOf(track, now_s, cursor);
  auto motion = motionAt(track, place);
  const double since_start = now_s - start.start_s;
  const bool blending = blend_time_s > 0.0 && since_start < blend_time_s;
  const double fraction = blendInto(start.offset, blend_time_s, since_start, motion);
  writeMotion(motion, active);
  const std::uint32_t settings = track.fields & ~(COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY);
  if (settings != 0) {
    settingsAt(track, place, settings_scratch);
    fadeSettings(start.from, settings_scratch, settings, fraction, active);
  }
  active.stamp_s = track.stamp_s;
  return blending || now_s < track.time_s[track.count - 1];
}

}  // namespace chunk

struct ChunkPlayer::Slots {
  int dof = 0;
  double blend_time_s = 0.0;
  std::array<std::atomic<std::uint8_t>, kSlots> state{};
  std::unique_ptr<chunk::Engine<chunk::Cartesian>> cartesian;
  std::unique_ptr<chunk::Engine<chunk::Joint>> joint;

  [[nodiscard]] std::uint64_t sequenceOf(int slot) const noexcept {
    return cartesian ? cartesian->tracks[slot].sequence : joint->tracks[slot].sequence;
  }
  [[nodiscard]] double takeoverOf(int slot) const noexcept {
    return cartesian ? cartesian->tracks[slot].takeover_s : joint->tracks[slot].takeover_s;
  }
  /// The running chunk, if any, becomes the previous one, ended at `now_s`.
  void retire(double now_s) noexcept {
    const auto retireIn = [&](auto& engine) {
      if (engine.running.sequence != 0) {
        engine.previous = engine.running;
        engine.previous_end_s = now_s;
        engine.running = {};
      }
    };
    if (cartesian) {
      retireIn(*cartesian);
    } else {
      retireIn(*joint);
    }
  }

  int acquire() noexcept {
    for (int slot = 0; slot < kSlots; ++slot) {
      if (state[slot].load(std::memory_order_acquire) == chunk::kFree) {
        return slot;
      }
    }
    return -1;
  }
};

}  // namespace comply::pipeline
