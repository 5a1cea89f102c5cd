#include "comply/pipeline/chunk_player.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

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

/// The difference between the reference in force and the chunk when the chunk starts, in value,
/// velocity and acceleration, which the blend lets decay to zero.
struct CartesianOffset {
  Vector3d position[3];
  Vector3d rotation[3];  ///< rotation vector (base frame) from the chunk's orientation to the old
};
struct JointOffset {
  JointVector position[3];
};

CartesianOffset offsetAt(const Cartesian& from, const CartesianMotion& chunk) noexcept {
  CartesianOffset offset;
  offset.position[0] = ConstVector3Map(from.position) - chunk.position;
  offset.position[1] = ConstVector3Map(from.twist) - chunk.velocity;
  offset.position[2] = ConstVector3Map(from.acceleration) - chunk.acceleration;
  // orientationError(a, b) is the base-frame rotation vector taking a to b.
  offset.rotation[0] = orientationError(chunk.orientation, fromXyzw(from.orientation));
  offset.rotation[1] = ConstVector3Map(from.twist + 3) - chunk.angular_velocity;
  offset.rotation[2] = ConstVector3Map(from.acceleration + 3) - chunk.angular_acceleration;
  return offset;
}

JointOffset offsetAt(const Joint& from, const JointMotion& chunk) noexcept {
  const int dof = from.dof;
  JointOffset offset;
  offset.position[0] = Eigen::Map<const Eigen::VectorXd>(from.position, dof) - chunk.position;
  offset.position[1] = Eigen::Map<const Eigen::VectorXd>(from.velocity, dof) - chunk.velocity;
  offset.position[2] =
      Eigen::Map<const Eigen::VectorXd>(from.acceleration, dof) - chunk.acceleration;
  return offset;
}

/// value, d/dt, d^2/dt^2 of a decaying offset `e` at blend fraction s of a blend of `length_s`.
template <typename Value>
void decay(const Value (&e)[3], const curve::QuinticWeights& w, double length_s, Value (&out)[3]) {
  const double t = length_s;
  out[0] = w.value[0] * e[0] + t * w.value[1] * e[1] + t * t * w.value[2] * e[2];
  out[1] = (w.first[0] * e[0] + t * w.first[1] * e[1] + t * t * w.first[2] * e[2]) / t;
  out[2] = (w.second[0] * e[0] + t * w.second[1] * e[1] + t * t * w.second[2] * e[2]) / (t * t);
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

void addOffset(const CartesianOffset& e, const curve::QuinticWeights& w, double length_s,
               CartesianMotion& m) noexcept {
  Vector3d position[3];
  Vector3d rotation[3];
  decay(e.position, w, length_s, position);
  decay(e.rotation, w, length_s, rotation);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
  // The rotation's rates add as vectors, which holds to first order in the offset's angle (the
  // exact rate of Exp(e) q has Jacobian terms in e): the offset is small when a chunk continues
  // the one before it, and the orientation itself stays continuous whatever its size.
  m.orientation = (quaternionExp(rotation[0]) * m.orientation).normalized();
  m.angular_velocity += rotation[1];
  m.angular_acceleration += rotation[2];
}

void addOffset(const JointOffset& e, const curve::QuinticWeights& w, double length_s,
               JointMotion& m) noexcept {
  JointVector position[3];
  decay(e.position, w, length_s, position);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
}

template <typename Bus>
using OffsetOf = std::conditional_t<std::is_same_v<Bus, Cartesian>, CartesianOffset, JointOffset>;

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
             double host_to_controller_s) {
  const int slot = slots.acquire();
  if (slot < 0) {
    return -1;
  }
  Track<Bus>& track = engine.tracks[slot];
  track.count = static_cast<int>(chunk.waypoints.size()) + 1;  // after the lead-in
  track.fields = static_cast<std::uint32_t>(chunk.fields);
  track.stamp_s = chunk.stamp_s;
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
  double fraction = 1.0;
  if (blending) {
    const curve::QuinticWeights w = curve::quinticDecay(std::max(0.0, since_start) / blend_time_s);
    addOffset(engine.offset, w, blend_time_s, motion);
    fraction = 1.0 - w.value[0];
  }
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

int ChunkPlayer::load(const CartesianChunk& chunk, double host_to_controller_s) {
  return slots_->cartesian ? loadInto(*slots_, *slots_->cartesian, chunk, host_to_controller_s)
                           : -1;
}

int ChunkPlayer::load(const JointChunk& chunk, double host_to_controller_s) {
  return slots_->joint ? loadInto(*slots_, *slots_->joint, chunk, host_to_controller_s) : -1;
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
