#include "comply/pipeline/chunk_player.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "chunk_blend.hpp"
#include "chunk_curve.hpp"
#include "chunk_track.hpp"
#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

using namespace chunk;  // NOLINT(google-build-using-namespace): the track's types and helpers

constexpr std::uint8_t kFree = 0;
constexpr std::uint8_t kLoaded = 1;

/// Fades the groups `fields` of `chunk` in from `from` (fraction 0: all `from`, 1: all chunk)
/// into `active`.
void fadeSettings(const Cartesian& from, const Cartesian& chunk, std::uint32_t fields,
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

void fadeSettings(const Joint& from, const Joint& chunk, std::uint32_t fields, double fraction,
                  Joint& active) noexcept {
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

void writeMotion(const CartesianMotion& m, Cartesian& to) noexcept {
  Vector3Map(to.position) = m.position;
  toXyzw(m.orientation, to.orientation);
  Eigen::Map<Vector6d>(to.twist) << m.velocity, m.angular_velocity;
  Eigen::Map<Vector6d>(to.acceleration) << m.acceleration, m.angular_acceleration;
}

void writeMotion(const JointMotion& m, Joint& to) noexcept {
  const int dof = to.dof;
  std::copy_n(m.position.data(), dof, to.position);
  std::copy_n(m.velocity.data(), dof, to.velocity);
  std::copy_n(m.acceleration.data(), dof, to.acceleration);
}

/// The typed half of the player: its slots and the running chunk's blend.
template <typename Bus>
struct Engine {
  std::array<Track<Bus>, ChunkPlayer::kSlots> tracks;
  Bus from{};  ///< the reference in force when the running chunk started
  OffsetOf<Bus> offset{};
  double start_s = 0.0;
  int cursor = 0;
  Bus settings{};  // scratch: the chunk's settings at this cycle's place
};

}  // namespace

struct ChunkPlayer::Slots {
  int kind = COMPLY_COMMAND_CARTESIAN;
  int dof = 0;
  double blend_time_s = 0.0;
  std::array<std::atomic<std::uint8_t>, kSlots> state{};
  std::unique_ptr<Engine<Cartesian>> cartesian;
  std::unique_ptr<Engine<Joint>> joint;

  int acquire() noexcept {
    for (int slot = 0; slot < kSlots; ++slot) {
      if (state[slot].load(std::memory_order_acquire) == kFree) {
        return slot;
      }
    }
    return -1;
  }
};

namespace {

template <typename Bus, typename Command>
int loadInto(ChunkPlayer::Slots& slots, Engine<Bus>& engine, const Chunk<Command>& chunk,
             double host_to_controller_s, std::uint64_t sequence) {
  const int slot = slots.acquire();
  if (slot < 0) {
    return -1;
  }
  Track<Bus>& track = engine.tracks[slot];
  track.count = static_cast<int>(chunk.waypoints.size()) + 1;  // after the lead-in
  track.fields = static_cast<std::uint32_t>(chunk.fields);
  track.stamp_s = chunk.stamp_s;
  track.sequence = sequence;
  for (int k = 1; k < track.count; ++k) {
    const ChunkWaypoint<Command>& waypoint = chunk.waypoints[k - 1];
    track.time_s[k] = waypoint.time_s + host_to_controller_s;
    track.waypoints[k] = schema::toBus(waypoint.command, slots.dof);
  }
  derive(track);
  slots.state[slot].store(kLoaded, std::memory_order_release);
  return slot;
}

template <typename Bus>
void startIn(Engine<Bus>& engine, int slot, const Bus& in_force, double now_s) noexcept {
  engine.from = in_force;
  engine.start_s = now_s;
  engine.cursor = 0;
  const Track<Bus>& track = engine.tracks[slot];
  engine.offset = offsetAt(in_force, motionAt(track, placeOf(track, now_s, engine.cursor)));
}

/// Returns whether the chunk still runs after `now_s`.
template <typename Bus>
bool playIn(Engine<Bus>& engine, int slot, double blend_time_s, double now_s,
            Bus& active) noexcept {
  const Track<Bus>& track = engine.tracks[slot];
  const Place place = placeOf(track, now_s, engine.cursor);
  auto motion = motionAt(track, place);
  const double since_start = now_s - engine.start_s;
  const bool blending = blend_time_s > 0.0 && since_start < blend_time_s;
  const double fraction = blendInto(engine.offset, blend_time_s, since_start, motion);
  writeMotion(motion, active);
  const std::uint32_t settings = track.fields & ~(COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY);
  if (settings != 0) {
    settingsAt(track, place, engine.settings);
    fadeSettings(engine.from, engine.settings, settings, fraction, active);
  }
  active.stamp_s = track.stamp_s;
  return blending || now_s < track.time_s[track.count - 1];
}

}  // namespace

ChunkPlayer::ChunkPlayer(int command_kind, int dof, double blend_time_s)
    : slots_(std::make_unique<Slots>()) {
  slots_->kind = command_kind;
  slots_->dof = dof;
  slots_->blend_time_s = std::max(0.0, blend_time_s);
  if (command_kind == COMPLY_COMMAND_CARTESIAN) {
    slots_->cartesian = std::make_unique<Engine<Cartesian>>();
  } else {
    slots_->joint = std::make_unique<Engine<Joint>>();
  }
}

ChunkPlayer::~ChunkPlayer() = default;

int ChunkPlayer::load(const CartesianChunk& chunk, double host_to_controller_s,
                      std::uint64_t sequence) {
  return slots_->cartesian
             ? loadInto(*slots_, *slots_->cartesian, chunk, host_to_controller_s, sequence)
             : -1;
}

int ChunkPlayer::load(const JointChunk& chunk, double host_to_controller_s,
                      std::uint64_t sequence) {
  return slots_->joint ? loadInto(*slots_, *slots_->joint, chunk, host_to_controller_s, sequence)
                       : -1;
}

void ChunkPlayer::release(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) {
    slots_->state[slot].store(kFree, std::memory_order_release);
  }
}

void ChunkPlayer::start(int slot, const CommandBus& in_force, double now_s) noexcept {
  if (slot < 0 || slot >= kSlots) {
    return;
  }
  if (playing_ >= 0 && playing_ != slot) {
    release(playing_);
  }
  playing_ = slot;
  // get_if: the buses are of the player's kind (one controller), and the cycle must not throw.
  if (const auto* cartesian = std::get_if<Cartesian>(&in_force); slots_->cartesian && cartesian) {
    startIn(*slots_->cartesian, slot, *cartesian, now_s);
  } else if (const auto* joint = std::get_if<Joint>(&in_force); slots_->joint && joint) {
    startIn(*slots_->joint, slot, *joint, now_s);
  } else {
    stop();
  }
}

bool ChunkPlayer::play(double now_s, CommandBus& active) noexcept {
  if (playing_ < 0) {
    return false;
  }
  bool running = false;
  if (auto* cartesian = std::get_if<Cartesian>(&active); slots_->cartesian && cartesian) {
    running = playIn(*slots_->cartesian, playing_, slots_->blend_time_s, now_s, *cartesian);
  } else if (auto* joint = std::get_if<Joint>(&active); slots_->joint && joint) {
    running = playIn(*slots_->joint, playing_, slots_->blend_time_s, now_s, *joint);
  }
  if (!running) {
    stop();
  }
  return running;
}

void ChunkPlayer::stop() noexcept {
  release(playing_);
  playing_ = -1;
}

bool ChunkPlayer::dropWaiting(std::uint64_t sequence, double now_s) noexcept {
  if (playing_ < 0) {
    return false;
  }
  const auto waits = [&](const auto& track) {
    return (sequence == 0 || track.sequence == sequence) && now_s < track.time_s[1];
  };
  const bool waiting = slots_->cartesian ? waits(slots_->cartesian->tracks[playing_])
                                         : waits(slots_->joint->tracks[playing_]);
  if (waiting) {
    stop();
  }
  return waiting;
}

std::uint32_t ChunkPlayer::fields() const noexcept {
  if (playing_ < 0) {
    return 0;
  }
  return slots_->cartesian ? slots_->cartesian->tracks[playing_].fields
                           : slots_->joint->tracks[playing_].fields;
}

double ChunkPlayer::stamp() const noexcept {
  if (playing_ < 0) {
    return 0.0;
  }
  return slots_->cartesian ? slots_->cartesian->tracks[playing_].stamp_s
                           : slots_->joint->tracks[playing_].stamp_s;
}

}  // namespace comply::pipeline
