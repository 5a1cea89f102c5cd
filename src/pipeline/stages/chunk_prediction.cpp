// ChunkPlayer::predict (chunk_player.hpp): off the cycle, what the cycle will write at given times
// if no new chunk arrives, from the view the cycle publishes and the slots it names.

#include <algorithm>
#include <cmath>
#include <limits>

#include "chunk_engine.hpp"

namespace comply::pipeline {
namespace {

using namespace chunk;  // NOLINT(google-build-using-namespace): the track's types and helpers

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
        // The waiting chunk starts at its takeover time (takeOverDue()), from the running
        // chunk's reference then; the cycle that meets it is the first to play it.
        const Track<Bus>& track = engine.tracks[view.waiting_slot];
        const double start_s = std::min(track.takeover_s, waiting_start_s);
        Bus from = *bus;
        if (running) {
          int c = 0;
          (void)evaluate(engine.tracks[view.running.slot], view.running, blend_time_s, start_s, c,
                         engine.predicted_settings, from);
        }
        engine.predicted_start = startOf(track, view.waiting_slot, from, start_s);
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

}  // namespace comply::pipeline
