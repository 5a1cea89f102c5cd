// A full lane by the recorder's policy (RecorderOptions::when_full), with a writer that cannot
// keep up: its encoder holds it until the test lets it go. kDrop refuses every record the lane
// has no room for and counts it, the producer never waits; kWait holds the producer until the
// writer has drained room (waking a writer that sleeps), and every record reaches the file.

#include <gtest/gtest.h>

#include <array>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>

#include "comply/record/mcap_reader.hpp"
#include "comply/record/recorder.hpp"
#include "scratch.hpp"

namespace comply::record {
namespace {

namespace fs = std::filesystem;

struct Sample {
  std::uint64_t index = 0;
  std::array<double, 40> values{};
};

/// Closed until release(): the writer thread waits in it.
class Gate {
 public:
  void pass() {
    std::unique_lock lock(mutex_);
    opened_.wait(lock, [this] { return open_; });
  }
  void release() {
    {
      const std::lock_guard lock(mutex_);
      open_ = true;
    }
    opened_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable opened_;
  bool open_ = false;
};

/// A recorder of Samples on one small lane (4 KiB: 9 samples), its encoder held by `gate`.
struct HeldRecorder {
  HeldRecorder(const fs::path& path, WhenFull when_full, Gate& gate)
      : recorder({.path = path.string(),
                  .mcap = {},
                  .writer_period_s = 3600.0,  // asleep unless a producer or stop() wakes it
                  .when_full = when_full}) {
    const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
    channel = recorder.addChannel(schema, "/samples", [&gate](auto raw, auto& out) {
      gate.pass();
      out.assign(raw.begin(), raw.begin() + 8);  // the index
    });
    lane = &recorder.addLane("control", 4096);
    recorder.start();
  }
  bool push(std::uint64_t index) {
    Sample sample;
    sample.index = index;
    return lane->push(channel, static_cast<std::int64_t>(index), sample);
  }

  Recorder recorder;
  std::uint16_t channel = 0;
  RecordLane* lane = nullptr;
};

/// The indexes in the file, in its order, and its comply_recording metadata.
std::vector<std::uint64_t> indexesIn(const fs::path& path, StringMap& recording) {
  std::vector<std::uint64_t> indexes;
  const McapContents contents = readMcap(path.string(), [&](const McapMessageView& m) {
    std::uint64_t index = 0;
    std::memcpy(&index, m.data.data(), sizeof index);
    indexes.push_back(index);
  });
  EXPECT_TRUE(contents.complete) << contents.stopped;
  for (const auto& [name, map] : contents.metadata) {
    if (name == "comply_recording") {
      recording = map;
    }
  }
  return indexes;
}

constexpr std::uint64_t kRecords = 300;

TEST(RecorderWhenFull, DropRefusesWhatTheLaneHasNoRoomForAndCountsIt) {
  const fs::path path = testing::scratchPath("comply_when_full", "drop.mcap");
  Gate gate;
  HeldRecorder held(path, WhenFull::kDrop, gate);
  std::uint64_t accepted = 0;
  for (std::uint64_t i = 0; i < kRecords; ++i) {
    accepted += held.push(i) ? 1 : 0;  // never waits: the writer is held throughout
  }
  EXPECT_LT(accepted, 10U) << "a 4 KiB lane holds 9 samples";
  EXPECT_EQ(held.lane->dropped(), kRecords - accepted);
  gate.release();
  held.recorder.stop();
  const RecorderStats stats = held.recorder.stats();
  EXPECT_EQ(stats.written, accepted);
  EXPECT_EQ(stats.dropped, kRecords - stats.written);
  StringMap recording;
  const std::vector<std::uint64_t> indexes = indexesIn(path, recording);
  EXPECT_EQ(indexes.size(), accepted);
  EXPECT_EQ(recording["when_full"], "drop");
  EXPECT_EQ(recording["records_dropped"], std::to_string(kRecords - accepted));
}

TEST(RecorderWhenFull, WaitHoldsTheProducerUntilTheWriterHasRoomAndLosesNothing) {
  const fs::path path = testing::scratchPath("comply_when_full", "wait.mcap");
  Gate gate;
  HeldRecorder held(path, WhenFull::kWait, gate);
  // Let the writer go once the producer has filled part of the lane: from there on it can only
  // go on by waiting for room.
  std::thread releaser([&] {
    while (held.lane->pushed() < 4) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    gate.release();
  });
  std::uint64_t refused = 0;
  for (std::uint64_t i = 0; i < kRecords; ++i) {
    refused += held.push(i) ? 0 : 1;
  }
  releaser.join();
  held.recorder.stop();
  EXPECT_EQ(refused, 0U);
  const RecorderStats stats = held.recorder.stats();
  EXPECT_EQ(stats.dropped, 0U);
  EXPECT_EQ(stats.written, kRecords);
  StringMap recording;
  const std::vector<std::uint64_t> indexes = indexesIn(path, recording);
  ASSERT_EQ(indexes.size(), kRecords);
  for (std::uint64_t i = 0; i < kRecords; ++i) {
    ASSERT_EQ(indexes[i], i);
  }
  EXPECT_EQ(recording["when_full"], "wait");
  EXPECT_EQ(recording["records_dropped"], "0");
}

TEST(RecorderWhenFull, AWaitingProducerIsLetGoWhenTheRecordingStops) {
  const fs::path path = testing::scratchPath("comply_when_full", "stopped.mcap");
  Gate gate;
  HeldRecorder held(path, WhenFull::kWait, gate);
  std::uint64_t accepted = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kRecords; ++i) {
      accepted += held.push(i) ? 1 : 0;
    }
  });
  while (held.lane->pushed() < 4) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  gate.release();
  held.recorder.stop();
  producer.join();  // a producer left waiting would hang here (the test's timeout)
  EXPECT_EQ(accepted, held.lane->pushed());
  EXPECT_EQ(held.lane->dropped(), 0U);
  EXPECT_EQ(held.recorder.stats().dropped, 0U);
}

}  // namespace
}  // namespace comply::record
