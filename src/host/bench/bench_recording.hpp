#pragma once
// What recording costs the cycle (`comply bench`, wrapper cartesian_recorded): after each cycle
// the state sample is filled and the cycle pushed by the live host's CycleRecorder into a control
// lane of its size, as `comply run --record` does. The lane's writer thread reads every byte of
// every record (so the lane's cache lines travel to the other core as they do under the real
// encoder) and keeps up with cycles run back to back, which the real encoder (about 12 us a
// record) would not: a robot's cycles come 1 ms apart. Should the writer still fall behind (its
// thread descheduled), the next cycle waits, untimed, for room, as a robot's millisecond between
// cycles would give it: a push that met a full lane would time a drop instead of a push (one
// still ends the benchmark with an error).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/record/recorder.hpp"

namespace comply::host {

template <typename Command>
class BenchRecording final : public hardware::LoopObserver {
 public:
  using Clock = std::chrono::steady_clock;

  BenchRecording(int warmup, const pipeline::Wrapper<Command>& wrapper,
                 const std::filesystem::path& file)
      : warmup_(warmup),
        wrapper_(wrapper),
        sampler_(wrapper),
        recorder_({.path = file.string(), .mcap = {}, .writer_period_s = 1e-4}),
        lane_(recorder_.addLane("control", host::kControlLaneBytes)) {
    const auto schema = recorder_.addSchema("bench", "ros2msg", "");
    const auto cycle_channel = recorder_.addChannel(
        schema, "/bench/cycle", [this](std::span<const std::uint8_t> raw, auto& out) {
          const std::uint64_t sum = read(raw);
          out.assign(reinterpret_cast<const std::uint8_t*>(&sum),
                     reinterpret_cast<const std::uint8_t*>(&sum) + sizeof sum);
        });
    const auto in_force_channel =
        recorder_.addInternal([this](std::span<const std::uint8_t> raw) { read(raw); });
    cycles_.emplace(lane_, cycle_channel, in_force_channel);
    recorder_.start();
  }

  void afterCycle(const hardware::CycleRecord& record) override {
    while (lane_.freeBytes() < kRoomBytes) {
      std::this_thread::yield();
    }
    const Clock::time_point start = Clock::now();
    sampler_.fill(record, *record.state, transport::Stamp::now(), sample_);
    const Clock::time_point filled = Clock::now();
    cycles_->push(sample_, std::get<pipeline::BusOf<Command>>(wrapper_.controller().lawBus()),
                  record.compute_s, record.start_lateness_s);
    const Clock::time_point end = Clock::now();
    if (record.index >= static_cast<std::uint64_t>(warmup_)) {
      cycle_us.push_back(record.controller_s * 1e6 + microseconds(filled, end));
      push_us.push_back(microseconds(filled, end));
      sample_us.push_back(microseconds(start, filled));
    }
  }

  /// Stops the writer, removes the file; throws when a push met a full lane.
  void finish() {
    recorder_.stop();
    std::filesystem::remove(recorder_.path());
    if (lane_.dropped() > 0) {
      throw std::runtime_error("the recording's lane was full " + std::to_string(lane_.dropped()) +
                               " times during the benchmark: its push timings would mix in drops");
    }
  }

  /// Pushes into a full lane, its writer never draining: what a drop costs [us].
  std::vector<double> fullLanePushes(int warmup, int iterations) const {
    const std::string path = recorder_.path() + ".full";
    record::Recorder stalled({.path = path, .mcap = {}, .writer_period_s = 3600.0});
    const auto schema = stalled.addSchema("bench", "ros2msg", "");
    const auto channel = stalled.addChannel(schema, "/bench/cycle");
    const auto in_force = stalled.addInternal([](std::span<const std::uint8_t>) {});
    record::RecordLane& lane = stalled.addLane("control", host::kControlLaneBytes);
    host::CycleRecorder<Command> cycles(lane, channel, in_force);
    stalled.start();
    auto bus = std::get<pipeline::BusOf<Command>>(wrapper_.controller().lawBus());
    std::vector<double> us;
    us.reserve(static_cast<std::size_t>(iterations));
    for (int i = 0; i < warmup + iterations; ++i) {
      bus.stamp_s = i;  // a new command every cycle: the dearest case
      const Clock::time_point start = Clock::now();
      cycles.push(sample_, bus, 0.0, 0.0);
      const Clock::time_point end = Clock::now();
      if (i >= warmup) {
        us.push_back(microseconds(start, end));
      }
    }
    stalled.stop();
    std::filesystem::remove(path);
    return us;
  }

  std::vector<double> cycle_us;   ///< the controller's cycle plus the push
  std::vector<double> push_us;    ///< the push alone
  std::vector<double> sample_us;  ///< filling the state sample (done without recording too)

 private:
  static double microseconds(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::micro>(to - from).count();
  }

  /// Room for a cycle's records (the cycle and a command in force, about 2 KB) with margin.
  static constexpr std::size_t kRoomBytes = 16 * 1024;

  int warmup_;
  const pipeline::Wrapper<Command>& wrapper_;
  host::StateSampler<Command> sampler_;
  host::StateSample sample_;
  /// The writer thread's read of a record: every byte, as an encoder reads them.
  std::uint64_t read(std::span<const std::uint8_t> raw) {
    checksum_ += std::accumulate(raw.begin(), raw.end(), std::uint64_t{0});
    return checksum_;
  }

  record::Recorder recorder_;
  record::RecordLane& lane_;
  std::optional<host::CycleRecorder<Command>> cycles_;
  std::uint64_t checksum_ = 0;  // the writer thread's
};

}  // namespace comply::host
