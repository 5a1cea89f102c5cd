// The recorder: every pushed record reaches the file in order, across lane wrap-arounds; a full
// lane drops whole records and counts them (in stats() and in the file); a push never allocates;
// an unwritable path is refused at once, a missing folder named and not made; a file-size limit
// stops the recording with a named error while the producer goes on pushing.

#include "comply/record/recorder.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "allocation_counter.hpp"
#include "comply/record/mcap_reader.hpp"
#include "scratch.hpp"

namespace comply::record {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return testing::scratchPath("comply_recorder", name);
}

/// A fixed-size sample as a control cycle pushes it.
struct Sample {
  std::uint64_t index = 0;
  std::array<double, 40> values{};
};

/// The encoder a host would give: here the index and first value, 16 bytes.
void encodeSample(std::span<const std::uint8_t> raw, std::vector<std::uint8_t>& out) {
  Sample sample;
  ASSERT_EQ(raw.size(), sizeof sample);
  std::memcpy(&sample, raw.data(), sizeof sample);
  out.resize(16);
  std::memcpy(out.data(), &sample.index, 8);
  std::memcpy(out.data() + 8, sample.values.data(), 8);
}

std::uint64_t metadataCount(const McapContents& contents, const std::string& key) {
  for (const auto& [name, map] : contents.metadata) {
    if (name == "comply_recording") {
      return std::stoull(map.at(key));
    }
  }
  ADD_FAILURE() << "no comply_recording metadata";
  return 0;
}

TEST(Recorder, EveryRecordReachesTheFileInOrder) {
  const fs::path path = scratch("order.mcap");
  Recorder recorder({.path = path.string(), .mcap = {}});
  const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
  const auto samples = recorder.addChannel(schema, "/samples", encodeSample);
  const auto notes = recorder.addChannel(schema, "/notes");
  // A small lane (4 KiB: 12 samples) that the producer wraps around many times.
  RecordLane& control = recorder.addLane("control", 4096);
  RecordLane& side = recorder.addLane("side", 4096);
  recorder.start();
  constexpr std::uint64_t kCount = 5000;
  std::uint64_t refused = 0;  // a refused push is a dropped record, retried here
  for (std::uint64_t i = 0; i < kCount; ++i) {
    Sample sample;
    sample.index = i;
    sample.values[0] = 0.5 * static_cast<double>(i);
    // Waits for room, as a test may (a cycle never does): nothing is dropped.
    while (!control.push(samples, static_cast<std::int64_t>(i) * 1000, sample)) {
      ++refused;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (i % 100 == 0) {
      const std::string note = "note " + std::to_string(i);  // a variable-size record
      while (!side.push(notes, static_cast<std::int64_t>(i) * 1000, note.data(), note.size())) {
        ++refused;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    }
  }
  recorder.stop();
  const RecorderStats stats = recorder.stats();
  EXPECT_TRUE(stats.error.empty()) << stats.error;
  EXPECT_EQ(stats.written, kCount + kCount / 100);
  EXPECT_FALSE(stats.recording);

  std::uint64_t next_sample = 0;
  std::uint64_t next_note = 0;
  const McapContents contents = readMcap(path.string(), [&](const McapMessageView& m) {
    if (m.channel_id == samples) {
      ASSERT_EQ(m.data.size(), 16U);
      std::uint64_t index = 0;
      double value = 0.0;
      std::memcpy(&index, m.data.data(), 8);
      std::memcpy(&value, m.data.data() + 8, 8);
      EXPECT_EQ(index, next_sample);
      EXPECT_EQ(value, 0.5 * static_cast<double>(next_sample));
      EXPECT_EQ(m.log_time_ns, next_sample * 1000);
      ++next_sample;
    } else {
      const std::string note(m.data.begin(), m.data.end());
      EXPECT_EQ(note, "note " + std::to_string(next_note * 100));
      ++next_note;
    }
  });
  EXPECT_TRUE(contents.complete) << contents.stopped;
  EXPECT_EQ(next_sample, kCount);
  EXPECT_EQ(next_note, kCount / 100);
  EXPECT_EQ(metadataCount(contents, "records_dropped"), refused);
  EXPECT_EQ(stats.dropped, refused);
  EXPECT_EQ(metadataCount(contents, "records_written"), kCount + kCount / 100);
}

TEST(Recorder, AFullLaneDropsWholeRecordsAndCountsThem) {
  const fs::path path = scratch("full.mcap");
  // The writer wakes every 200 ms: a burst of pushes meets a full lane.
  Recorder recorder({.path = path.string(), .mcap = {}, .writer_period_s = 0.2});
  const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
  const auto samples = recorder.addChannel(schema, "/samples", encodeSample);
  RecordLane& control = recorder.addLane("control", 4096);
  recorder.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the writer is now asleep
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;
  EXPECT_EQ(control.freeBytes(), control.capacity());
  for (std::uint64_t i = 0; i < 100; ++i) {
    Sample sample;
    sample.index = i;
    const std::size_t free_before = control.freeBytes();
    const bool pushed = control.push(samples, static_cast<std::int64_t>(i), sample);
    (pushed ? accepted : refused) += 1;
    // A record takes room (its head and bytes, aligned); a refused one takes none.
    EXPECT_EQ(control.freeBytes() < free_before, pushed) << i;
  }
  EXPECT_LT(control.freeBytes(), 2 * sizeof(Sample) + 128) << "full: less than a record's room";
  EXPECT_GT(refused, 0U);
  EXPECT_EQ(control.dropped(), refused);
  recorder.stop();
  EXPECT_EQ(recorder.stats().dropped, refused);
  EXPECT_EQ(recorder.stats().written, accepted);
  const McapContents contents = readMcap(path.string());
  EXPECT_EQ(contents.messages, accepted);
  EXPECT_EQ(metadataCount(contents, "records_dropped"), refused);
  EXPECT_EQ(metadataCount(contents, "control.records_dropped"), refused);
}

/// A record that is not trivially copyable (Eigen's types are not), as a cycle's is.
struct EigenRecord {
  Eigen::Quaterniond orientation;
  Eigen::Matrix<double, 7, 1> position;
  std::uint64_t index;
};

TEST(Recorder, AnEmplacedRecordReadsBackAsBuilt) {
  const fs::path path = scratch("emplace.mcap");
  Recorder recorder({.path = path.string(), .mcap = {}});
  const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
  std::vector<EigenRecord> seen;
  const auto channel =
      recorder.addChannel(schema, "/eigen", [&](std::span<const std::uint8_t> raw, auto& out) {
        seen.push_back(recordAs<EigenRecord>(raw));  // the writer thread
        out.assign(8, 0);
      });
  RecordLane& control = recorder.addLane("control", 1 << 16);
  recorder.start();
  testing::AllocationCounter counter;
  counter.start();
  for (std::uint64_t i = 0; i < 100; ++i) {
    const auto angle = static_cast<double>(i) * 0.01;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
    while (!control.emplace<EigenRecord>(channel, static_cast<std::int64_t>(i), q,
                                         Eigen::Matrix<double, 7, 1>::Constant(angle), i)) {
      std::this_thread::yield();
    }
  }
  EXPECT_EQ(counter.stop(), 0U);
  recorder.stop();
  ASSERT_EQ(seen.size(), 100U);
  for (std::uint64_t i = 0; i < 100; ++i) {
    const auto angle = static_cast<double>(i) * 0.01;
    EXPECT_EQ(seen[i].index, i);
    EXPECT_DOUBLE_EQ(seen[i].position[6], angle);
    EXPECT_NEAR(seen[i].orientation.angularDistance(
                    Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()))),
                0.0, 1e-12);
  }
}

TEST(Recorder, APushNeitherAllocatesNorBlocks) {
  const fs::path path = scratch("alloc.mcap");
  Recorder recorder({.path = path.string(), .mcap = {}});
  const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
  const auto samples = recorder.addChannel(schema, "/samples", encodeSample);
  RecordLane& control = recorder.addLane("control", 1 << 20);
  recorder.start();
  Sample sample;
  testing::AllocationCounter counter;
  counter.start();
  int accepted = 0;
  for (int i = 0; i < 2000; ++i) {
    sample.index = static_cast<std::uint64_t>(i);
    accepted += control.push(samples, i, sample) ? 1 : 0;
  }
  EXPECT_EQ(counter.stop(), 0U);
  recorder.stop();
  EXPECT_EQ(static_cast<std::uint64_t>(accepted) + control.dropped(), 2000U);
}

TEST(Recorder, AnUnwritablePathIsRefusedAtOnce) {
  try {
    Recorder recorder({.path = "/proc/comply-cannot-write-here.mcap", .mcap = {}});
    FAIL() << "a recorder opened an unwritable path";
  } catch (const McapError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot record to /proc/"), std::string::npos)
        << error.what();
  }
}

TEST(Recorder, AMissingFolderIsNamedAndNotMade) {
  const fs::path missing = scratch("missing");
  const fs::path path = missing / "deeper" / "run.mcap";
  try {
    Recorder recorder({.path = path.string(), .mcap = {}});
    FAIL() << "a recorder opened a file in a missing folder";
  } catch (const McapError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("cannot record to " + path.string() + ": the folder '" +
                        (missing / "deeper").string() +
                        "' does not exist (create it first: "
                        "mkdir -p '" +
                        (missing / "deeper").string() + "')"),
              std::string::npos)
        << text;
  }
  EXPECT_FALSE(fs::exists(missing));
  // A file where its folder should be is named as such.
  std::ofstream(missing.string()) << "a file";
  try {
    Recorder recorder({.path = (missing / "run.mcap").string(), .mcap = {}});
    FAIL() << "a recorder opened a file under a file";
  } catch (const McapError& error) {
    EXPECT_NE(std::string(error.what()).find("'" + missing.string() + "' is not a folder"),
              std::string::npos)
        << error.what();
  }
  fs::remove(missing);
}

// In a child process, so the file-size limit binds only there.
TEST(Recorder, AFileSizeLimitStopsTheRecordingNotTheProducer) {
  const fs::path path = scratch("limited.mcap");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{64 * 1024, 64 * 1024};  // 64 KiB: reached within the first second
    setrlimit(RLIMIT_FSIZE, &limit);
    Recorder recorder(
        {.path = path.string(), .mcap = {.compression = Compression::kNone, .chunk_bytes = 8192}});
    const auto schema = recorder.addSchema("test/msg/Sample", "ros2msg", "uint64 index\n");
    const auto samples = recorder.addChannel(schema, "/samples");
    RecordLane& control = recorder.addLane("control", 1 << 20);
    recorder.start();
    Sample sample;
    int pushed_after_error = 0;
    for (int i = 0; i < 3000; ++i) {  // 3 s of cycles at 1 kHz, 336 bytes each: 1 MB
      sample.index = static_cast<std::uint64_t>(i);
      control.push(samples, i, sample);
      if (!recorder.stats().error.empty()) {
        ++pushed_after_error;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    recorder.stop();
    const RecorderStats stats = recorder.stats();
    const bool named = stats.error.find("File too large") != std::string::npos &&
                       stats.error.find(path.string()) != std::string::npos;
    // Exit codes: 0 all as expected; 2 no error named; 3 the producer stopped early.
    _exit(!named ? 2 : pushed_after_error < 100 || stats.lost == 0 ? 3 : 0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child was killed (signal " << WTERMSIG(status) << ")";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  // What was written before the limit is still a readable recording.
  const McapContents contents = readMcap(path.string());
  EXPECT_GT(contents.messages, 0U);
  EXPECT_FALSE(contents.complete);
  EXPECT_LE(fs::file_size(path), 64U * 1024U);
}

}  // namespace
}  // namespace comply::record
