#include "comply/pipeline/chunk_player.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "chunk_blend.hpp"
#include "chunk_curve.hpp"
#include "chunk_track.hpp"
#include "comply/core/rotation.hpp"
#include "comply/core/triple_buffer.hpp"
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

}  // namespace

struct ChunkPlayer::Slots {
  int kind = COMPLY_COMMAND_CARTESIAN;
  int dof = 0;
  double blend_time_s = 0.0;
  std::array<std::atomic<std::uint8_t>, kSlots> state{};
  std::unique_ptr<Engine<Cartesian>> cartesian;
  std::unique_ptr<Engine<Joint>> joint;

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
             double host_to_controller_s, std::uint64_t sequence, double received_s) {
  const int slot = slots.acquire();
  if (slot < 0) {
    return -1;
  }
  Track<Bus>& track = engine.tracks[slot];
  track.count = static_cast<int>(chunk.waypoints.size()) + 1;  // after the lead-in
  track.fields = static_cast<std::uint32_t>(chunk.fields);
  track.stamp_s = chunk.stamp_s;
  track.sequence = sequence;
  track.observation_s = chunk.observation_s + host_to_controller_s;  // NaN stays NaN
  track.takeover_s = chunk.takeover_s + host_to_controller_s;
  track.received_s = received_s;
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

/// The seam of a chunk starting with `start` (chunk_timing.hpp).
void measureSeam(const CartesianOffset& offset, ChunkTiming& timing) noexcept {
  timing.position_jump = offset.position[0].norm();
  timing.velocity_jump = offset.position[1].norm();
  timing.rotation_jump = offset.rotation[0].norm();
  timing.angular_velocity_jump = offset.rotation[1].norm();
}

void measureSeam(const JointOffset& offset, ChunkTiming& timing) noexcept {
  timing.position_jump = offset.position[0].cwiseAbs().maxCoeff();
  timing.velocity_jump = offset.position[1].cwiseAbs().maxCoeff();
  timing.rotation_jump = 0.0;
  timing.angular_velocity_jump = 0.0;
}

/// The timing record's fields a track gives.
template <typename Bus>
void describe(const Track<Bus>& track, ChunkTiming& timing) noexcept {
  timing.sequence = track.sequence;
  timing.observation_s = track.observation_s;
  timing.received_s = track.received_s;
  timing.requested_takeover_s = track.takeover_s;
  timing.first_waypoint_s = track.time_s[1];
  timing.last_waypoint_s = track.time_s[track.count - 1];
  timing.waypoints = track.count - 1;
}

template <typename Bus>
void describeStart(const Track<Bus>& track, const Start<Bus>& start, ChunkTiming& timing) noexcept {
  describe(track, timing);
  timing.end = ChunkEnd::kTookOver;
  timing.takeover_s = start.start_s;
  int past = 0;
  for (int k = 1; k < track.count; ++k) {
    past += track.time_s[k] < start.start_s - ChunkPlayer::kTakeoverTolerance_s ? 1 : 0;
  }
  timing.waypoints_past = past;
  measureSeam(start.offset, timing);
}

template <typename Bus>
void publishView(Engine<Bus>& engine, int waiting_slot) noexcept {
  View<Bus> view;
  view.running = engine.running;
  view.previous = engine.previous;
  view.previous_end_s = engine.previous_end_s;
  view.waiting_slot = waiting_slot;
  view.waiting_sequence = waiting_slot >= 0 ? engine.tracks[waiting_slot].sequence : 0;
  engine.view.publishFromSoleWriter(view);
}

/// The first cycle of the grid `last_cycle_s` + j `period_s` (j >= 1) that meets `takeover_s`.
double takeoverCycle(double takeover_s, double last_cycle_s, double period_s) noexcept {
  const double wanted = takeover_s - ChunkPlayer::kTakeoverTolerance_s;
  const double steps = std::ceil((wanted - last_cycle_s) / period_s);
  return last_cycle_s + std::max(1.0, steps) * period_s;
}

template <typename Bus>
bool predictIn(Engine<Bus>& engine, double blend_time_s, std::span<const double> times_s,
               double last_cycle_s, double period_s, std::span<CommandBus> out) noexcept {
  engine.view.update();
  const View<Bus>& view = engine.view.read();
  // A slot holds a chunk's data until a load() reuses it, which the caller's lock excludes.
  const auto intact = [&](const Start<Bus>& start) {
    return start.sequence != 0 && engine.tracks[start.slot].sequence == start.sequence;
  };
  const bool running = intact(view.running);
  const bool previous = intact(view.previous);
  const bool waiting =
      view.waiting_slot >= 0 && engine.tracks[view.waiting_slot].sequence == view.waiting_sequence;
  double waiting_start_s = std::numeric_limits<double>::infinity();
  if (waiting) {
    waiting_start_s =
        takeoverCycle(engine.tracks[view.waiting_slot].takeover_s, last_cycle_s, period_s);
  }
  bool known = true;
  int cursor = 0;
  bool waiting_started = false;
  for (std::size_t k = 0; k < times_s.size() && k < out.size(); ++k) {
    Bus* bus = std::get_if<Bus>(&out[k]);
    if (bus == nullptr) {
      return false;
    }
    const double t = times_s[k];
    if (waiting && t >= waiting_start_s) {
      if (!waiting_started) {
        // The waiting chunk starts from the reference the cycle writes at its takeover.
        Bus from = *bus;
        if (running) {
          int c = 0;
          (void)evaluate(engine.tracks[view.running.slot], view.running, blend_time_s,
                         waiting_start_s, c, engine.predicted_settings, from);
        }
        engine.predicted_start =
            startOf(engine.tracks[view.waiting_slot], view.waiting_slot, from, waiting_start_s);
        waiting_started = true;
        cursor = 0;
      }
      (void)evaluate(engine.tracks[view.waiting_slot], engine.predicted_start, blend_time_s, t,
                     cursor, engine.predicted_settings, *bus);
    } else if (view.running.sequence != 0 && t >= view.running.start_s) {
      if (running) {
        (void)evaluate(engine.tracks[view.running.slot], view.running, blend_time_s, t, cursor,
                       engine.predicted_settings, *bus);
      } else {
        bus->position[0] = std::numeric_limits<double>::quiet_NaN();
        known = false;
      }
    } else if (view.previous.sequence != 0 && t < view.previous_end_s) {
      // Before the last change (a time already past): what the chunk before played then.
      if (previous && t >= view.previous.start_s) {
        int c = 0;
        (void)evaluate(engine.tracks[view.previous.slot], view.previous, blend_time_s, t, c,
                       engine.predicted_settings, *bus);
      } else {
        bus->position[0] = std::numeric_limits<double>::quiet_NaN();
        known = false;
      }
    }
  }
  return known;
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
                      std::uint64_t sequence, double received_s) {
  return slots_->cartesian ? loadInto(*slots_, *slots_->cartesian, chunk, host_to_controller_s,
                                      sequence, received_s)
                           : -1;
}

int ChunkPlayer::load(const JointChunk& chunk, double host_to_controller_s, std::uint64_t sequence,
                      double received_s) {
  return slots_->joint
             ? loadInto(*slots_, *slots_->joint, chunk, host_to_controller_s, sequence, received_s)
             : -1;
}

void ChunkPlayer::release(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) {
    slots_->state[slot].store(kFree, std::memory_order_release);
  }
}

bool ChunkPlayer::predict(std::span<const double> times_s, double last_cycle_s, double period_s,
                          std::span<CommandBus> out) {
  if (!(period_s > 0.0)) {
    return false;
  }
  return slots_->cartesian ? predictIn(*slots_->cartesian, slots_->blend_time_s, times_s,
                                       last_cycle_s, period_s, out)
                           : predictIn(*slots_->joint, slots_->blend_time_s, times_s, last_cycle_s,
                                       period_s, out);
}

ChunkTiming* ChunkPlayer::newEvent() noexcept {
  if (event_count_ >= kEventsPerCycle) {
    return nullptr;  // more than a cycle can produce: the oldest are kept
  }
  ChunkTiming* event = &events_[static_cast<std::size_t>(event_count_++)];
  *event = ChunkTiming{};
  return event;
}

void ChunkPlayer::publish() noexcept {
  if (slots_->cartesian) {
    publishView(*slots_->cartesian, waiting_);
  } else {
    publishView(*slots_->joint, waiting_);
  }
}

void ChunkPlayer::begin(int slot, const CommandBus& in_force, double now_s) noexcept {
  // get_if: the buses are of the player's kind (one controller), and the cycle must not throw.
  const auto startIn = [&](auto& engine, const auto& from) {
    const auto& track = engine.tracks[slot];
    engine.running = startOf(track, slot, from, now_s);
    engine.cursor = 0;
    if (ChunkTiming* timing = newEvent()) {
      describeStart(track, engine.running, *timing);
      timing->starved = playing_ < 0 && std::isfinite(ran_out_s_);
      timing->rest_s = timing->starved ? now_s - ran_out_s_ : 0.0;
    }
  };
  slots_->retire(now_s);  // the chunk it takes over from, if one plays
  if (const auto* cartesian = std::get_if<Cartesian>(&in_force); slots_->cartesian && cartesian) {
    startIn(*slots_->cartesian, *cartesian);
  } else if (const auto* joint = std::get_if<Joint>(&in_force); slots_->joint && joint) {
    startIn(*slots_->joint, *joint);
  } else {
    release(slot);
    stop();
    return;
  }
  if (playing_ >= 0 && playing_ != slot) {
    release(playing_);
  }
  playing_ = slot;
  ran_out_s_ = std::numeric_limits<double>::quiet_NaN();
  last_play_s_ = now_s;
  publish();
}

bool ChunkPlayer::take(int slot, const CommandBus& in_force, double now_s) noexcept {
  if (slot < 0 || slot >= kSlots) {
    return false;
  }
  const double takeover_s = slots_->takeoverOf(slot);
  if (waiting_ >= 0) {
    endWaiting(ChunkEnd::kSuperseded);
  }
  // It waits even when none plays (the reference in force holds): the intake checked it from
  // the reference at its takeover, which is this one.
  if (takeover_s - kTakeoverTolerance_s > now_s) {
    waiting_ = slot;
    publish();
    return false;
  }
  begin(slot, in_force, now_s);
  return true;
}

std::uint64_t ChunkPlayer::takeOverDue(double now_s, CommandBus& active) noexcept {
  if (waiting_ < 0) {
    return 0;
  }
  if (slots_->takeoverOf(waiting_) - kTakeoverTolerance_s > now_s) {
    return 0;
  }
  const int slot = waiting_;
  waiting_ = -1;
  if (playing_ >= 0) {
    (void)play(now_s, active);  // the running chunk's reference at this time, where it starts
  }
  const std::uint64_t sequence = slots_->sequenceOf(slot);
  begin(slot, active, now_s);
  return sequence;
}

bool ChunkPlayer::play(double now_s, CommandBus& active) noexcept {
  if (playing_ < 0) {
    return false;
  }
  last_play_s_ = now_s;
  bool running = false;
  if (auto* cartesian = std::get_if<Cartesian>(&active); slots_->cartesian && cartesian) {
    Engine<Cartesian>& e = *slots_->cartesian;
    running = evaluate(e.tracks[playing_], e.running, slots_->blend_time_s, now_s, e.cursor,
                       e.settings, *cartesian);
  } else if (auto* joint = std::get_if<Joint>(&active); slots_->joint && joint) {
    Engine<Joint>& e = *slots_->joint;
    running = evaluate(e.tracks[playing_], e.running, slots_->blend_time_s, now_s, e.cursor,
                       e.settings, *joint);
  }
  if (!running) {
    release(playing_);
    playing_ = -1;
    ran_out_s_ = now_s;
    slots_->retire(now_s);  // from now the reference in force holds its last waypoint
    publish();
  }
  return running;
}

void ChunkPlayer::endWaiting(ChunkEnd end) noexcept {
  if (waiting_ < 0) {
    return;
  }
  if (ChunkTiming* timing = newEvent()) {
    if (slots_->cartesian) {
      describe(slots_->cartesian->tracks[waiting_], *timing);
    } else {
      describe(slots_->joint->tracks[waiting_], *timing);
    }
    timing->end = end;
  }
  release(waiting_);
  waiting_ = -1;
}

void ChunkPlayer::stop() noexcept {
  endWaiting(ChunkEnd::kDropped);
  release(playing_);
  playing_ = -1;
  ran_out_s_ = std::numeric_limits<double>::quiet_NaN();
  slots_->retire(last_play_s_);  // the reference in force is what play() last wrote
  publish();
}

bool ChunkPlayer::dropWaiting(std::uint64_t sequence, double now_s) noexcept {
  if (waiting_ >= 0 && (sequence == 0 || slots_->sequenceOf(waiting_) == sequence)) {
    endWaiting(ChunkEnd::kDropped);
    publish();
  }
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
  std::uint32_t fields = 0;
  for (const int slot : {playing_, waiting_}) {
    if (slot >= 0) {
      fields |= slots_->cartesian ? slots_->cartesian->tracks[slot].fields
                                  : slots_->joint->tracks[slot].fields;
    }
  }
  return fields;
}

double ChunkPlayer::stamp() const noexcept {
  if (playing_ < 0) {
    return 0.0;
  }
  return slots_->cartesian ? slots_->cartesian->tracks[playing_].stamp_s
                           : slots_->joint->tracks[playing_].stamp_s;
}

}  // namespace comply::pipeline
