#include "comply/pipeline/chunk_player.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "chunk_engine.hpp"

namespace comply::pipeline {
namespace {

using namespace chunk;  // NOLINT(google-build-using-namespace): the track's types and helpers

template <typename Bus, typename Command>
int loadInto(ChunkPlayer::Slots& slots, Engine<Bus>& engine, const Chunk<Command>& chunk,
             double host_to_controller_s, std::uint64_t sequence, double received_s,
             const CommandBus* joins) {
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
  derive(track, joins != nullptr ? std::get_if<Bus>(joins) : nullptr);
  slots.state[slot].store(kLoaded, std::memory_order_release);
  return slot;
}

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
}  // namespace

ChunkPlayer::ChunkPlayer(int command_kind, int dof, double blend_time_s)
    : slots_(std::make_unique<Slots>()) {
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
                      std::uint64_t sequence, double received_s, const CommandBus* joins) {
  return slots_->cartesian ? loadInto(*slots_, *slots_->cartesian, chunk, host_to_controller_s,
                                      sequence, received_s, joins)
                           : -1;
}

int ChunkPlayer::load(const JointChunk& chunk, double host_to_controller_s, std::uint64_t sequence,
                      double received_s, const CommandBus* joins) {
  return slots_->joint ? loadInto(*slots_, *slots_->joint, chunk, host_to_controller_s, sequence,
                                  received_s, joins)
                       : -1;
}

void ChunkPlayer::release(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) {
    slots_->state[slot].store(kFree, std::memory_order_release);
  }
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
  // It starts at its takeover time, which fell after the last cycle: from the running chunk's
  // reference then, so a chunk that continues that curve there (a policy's committed prefix)
  // continues it exactly, wherever the cycles fall; this cycle plays it from there.
  const double start_s = std::min(slots_->takeoverOf(slot), now_s);
  if (playing_ >= 0) {
    (void)play(start_s, active);
  }
  const std::uint64_t sequence = slots_->sequenceOf(slot);
  begin(slot, active, start_s);
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
