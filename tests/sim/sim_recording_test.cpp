// What a recording keeps when its writer cannot keep up (a control lane of 4 KiB, about three
// cycles, and a writer that sleeps unless a producer wakes it): one that waits, as the offline
// hosts' do (comply sim, comply.Sim), holds every cycle pushed and counts no drop; one that
// drops, as comply run's does, counts exactly the cycles it did not write. And `comply sim`'s
// own recording holds one cycle record per cycle run, and says it waited.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "comply/host/host_recording.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/record/mcap_reader.hpp"
#include "scratch.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

namespace fs = std::filesystem;

struct Recorded {
  std::uint64_t cycles = 0;     ///< /comply/cycle messages
  record::StringMap recording;  ///< the comply_recording metadata
};

Recorded readRecording(const fs::path& path) {
  Recorded recorded;
  std::uint16_t cycle_channel = 0xFFFF;
  const record::McapContents contents = record::readMcap(path.string());
  EXPECT_TRUE(contents.complete) << contents.stopped;
  for (const auto& channel : contents.channels) {
    if (channel.topic == "/comply/cycle") {
      cycle_channel = channel.id;
    }
  }
  record::readMcap(path.string(), [&](const record::McapMessageView& m) {
    recorded.cycles += m.channel_id == cycle_channel ? 1 : 0;
  });
  for (const auto& [name, map] : contents.metadata) {
    if (name == "comply_recording") {
      recorded.recording = map;
    }
  }
  return recorded;
}

constexpr std::uint64_t kCycles = 2000;

/// kCycles cycles as a control thread records them, into a recording whose writer cannot keep up.
record::RecorderStats recordCycles(const fs::path& path, record::WhenFull when_full) {
  const auto resolved = pipeline::resolveController(simCartesianConfig("fr3"));
  host::HostRecording recording(
      path.string(), resolved, "comply", {{"host", "test"}},
      {.when_full = when_full, .control_lane_bytes = 4096, .writer_period_s = 3600.0});
  host::StateSample sample;
  const pipeline::BusOf<CartesianCommand> in_force{};
  for (std::uint64_t i = 0; i < kCycles; ++i) {
    sample.cycle = i;
    sample.wall = transport::Stamp::fromNanoseconds(static_cast<std::int64_t>(i) * 1'000'000);
    recording.cycle<CartesianCommand>(sample, in_force, 1e-6, 0.0);
  }
  recording.stop();
  return recording.stats();
}

TEST(SlowWriter, ARecordingThatWaitsKeepsEveryCycle) {
  const ScratchDir folder("wait_recording");
  const record::RecorderStats stats =
      recordCycles(folder.path() / "wait.mcap", record::WhenFull::kWait);
  EXPECT_EQ(stats.error, "");
  EXPECT_EQ(stats.dropped, 0U);
  const Recorded recorded = readRecording(folder.path() / "wait.mcap");
  EXPECT_EQ(recorded.cycles, kCycles);
  EXPECT_EQ(recorded.recording.at("records_dropped"), "0");
  EXPECT_EQ(recorded.recording.at("when_full"), "wait");
}

TEST(SlowWriter, ARecordingThatDropsCountsEveryCycleNotWritten) {
  const ScratchDir folder("drop_recording");
  const record::RecorderStats stats =
      recordCycles(folder.path() / "drop.mcap", record::WhenFull::kDrop);
  EXPECT_EQ(stats.error, "");
  const Recorded recorded = readRecording(folder.path() / "drop.mcap");
  EXPECT_GT(stats.dropped, 0U);
  // The command in force went with the first cycle, into an empty lane: every drop is a cycle.
  EXPECT_EQ(stats.dropped, kCycles - recorded.cycles);
  EXPECT_EQ(recorded.recording.at("records_dropped"), std::to_string(stats.dropped));
  EXPECT_EQ(recorded.recording.at("when_full"), "drop");
}

TEST(SlowWriter, ComplySimRecordsOneCycleRecordPerCycleRun) {
  const ScratchDir folder("sim_recording");
  host::SimRunOptions run = fr3ExampleRun("press_on_table.yaml");
  run.duration_s = 0.5;
  run.record_path = folder.path() / "sim.mcap";
  const host::SimResult result = host::runSimulation(run);
  ASSERT_TRUE(result.summary.recording.has_value());
  EXPECT_EQ(result.summary.recording->dropped, 0U);
  EXPECT_EQ(result.summary.recording->error, "");
  const Recorded recorded = readRecording(run.record_path);
  EXPECT_EQ(recorded.cycles, result.log.time_s.size());
  EXPECT_GT(recorded.cycles, 400U);
  EXPECT_EQ(recorded.recording.at("when_full"), "wait");
}

}  // namespace
}  // namespace comply::testing
