// The MCAP writer against comply's streaming reader: what was written reads back (schemas,
// channels, every message with its times and bytes, metadata, the summary's statistics), with and
// without zstd; chunks close by size and by time span; a file cut anywhere reads up to its last
// complete chunk; a damaged chunk and a file that is not MCAP are named. The independent readers
// (Node's @mcap/core, Python's comply.read_recording) check the same files in their own tests.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "comply/record/mcap_reader.hpp"
#include "comply/record/mcap_writer.hpp"
#include "scratch.hpp"

namespace comply::record {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return testing::scratchPath("comply_mcap", name);
}

std::vector<std::uint8_t> payload(std::uint64_t i) {
  std::vector<std::uint8_t> bytes(8 + i % 50);
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    bytes[k] = static_cast<std::uint8_t>(i * 31 + k);
  }
  return bytes;
}

struct Written {
  std::uint64_t messages = 0;
  std::uint64_t chunks = 0;
};

/// 1000 messages on two channels, 1 ms apart, into `path`. With `crashed`: the file as a killed
/// process leaves it (flushed, never closed) is copied there before the writer closes `path`.
Written writeFile(const fs::path& path, McapWriterOptions options,
                  const fs::path* crashed = nullptr) {
  McapWriter writer(path.string(), options);
  const std::uint16_t schema = writer.addSchema("pkg/msg/A", "ros2msg", "float64 x\n");
  const std::uint16_t a = writer.addChannel(schema, "/a", "cdr", {{"k", "v"}});
  const std::uint16_t b = writer.addChannel(schema, "/b", "cdr", {});
  for (std::uint64_t i = 0; i < 1000; ++i) {
    writer.write(i % 3 == 0 ? b : a, 1'000'000'000 + i * 1'000'000, 7 + i, payload(i));
  }
  writer.addMetadata("comply_recording", {{"records_dropped", "0"}});
  Written written{writer.messageCount(), 0};
  if (crashed != nullptr) {
    writer.flush();
    fs::copy_file(path, *crashed, fs::copy_options::overwrite_existing);
  }
  writer.close();
  written.chunks = writer.chunkCount();
  return written;
}

void expectAllMessages(const fs::path& path, std::uint64_t count) {
  std::uint64_t seen = 0;
  readMcap(path.string(), [&](const McapMessageView& m) {
    const std::uint64_t i = seen++;
    EXPECT_EQ(m.channel_id, i % 3 == 0 ? 1 : 0);
    EXPECT_EQ(m.log_time_ns, 1'000'000'000 + i * 1'000'000);
    EXPECT_EQ(m.publish_time_ns, 7 + i);
    const std::vector<std::uint8_t> expected = payload(i);
    ASSERT_EQ(m.data.size(), expected.size());
    EXPECT_TRUE(std::equal(m.data.begin(), m.data.end(), expected.begin()));
  });
  EXPECT_EQ(seen, count);
}

class McapFile : public ::testing::TestWithParam<Compression> {};

TEST_P(McapFile, ReadsBackWhatWasWritten) {
  const fs::path path = scratch("round_trip.mcap");
  const Written written = writeFile(path, {.compression = GetParam(), .chunk_bytes = 4096});
  EXPECT_GT(written.chunks, 3U);  // several chunks, so the index and offsets are exercised

  const McapContents contents = readMcap(path.string());
  EXPECT_TRUE(contents.complete) << contents.stopped;
  EXPECT_EQ(contents.profile, "ros2");
  EXPECT_EQ(contents.library, "comply");
  ASSERT_EQ(contents.channels.size(), 2U);
  EXPECT_EQ(contents.channels[0].topic, "/a");
  EXPECT_EQ(contents.channels[0].schema_name, "pkg/msg/A");
  EXPECT_EQ(contents.channels[0].schema_encoding, "ros2msg");
  EXPECT_EQ(contents.channels[0].schema_data, "float64 x\n");
  EXPECT_EQ(contents.channels[0].metadata.at("k"), "v");
  EXPECT_EQ(contents.channels[1].topic, "/b");
  EXPECT_EQ(contents.messages, 1000U);
  EXPECT_EQ(contents.chunks, written.chunks);
  ASSERT_TRUE(contents.statistics.has_value());
  EXPECT_EQ(contents.statistics->message_count, 1000U);
  EXPECT_EQ(contents.statistics->chunk_count, written.chunks);
  EXPECT_EQ(contents.statistics->message_start_time_ns, 1'000'000'000U);
  EXPECT_EQ(contents.statistics->message_end_time_ns, 1'000'000'000U + 999 * 1'000'000U);
  EXPECT_EQ(contents.statistics->channel_message_counts.at(1), 334U);
  EXPECT_EQ(contents.statistics->channel_message_counts.at(0), 666U);
  ASSERT_EQ(contents.metadata.size(), 1U);
  EXPECT_EQ(contents.metadata[0].first, "comply_recording");
  expectAllMessages(path, 1000);
}

TEST_P(McapFile, ChunksCloseAfterTheirTimeSpan) {
  const fs::path path = scratch("span.mcap");
  // 1000 messages over 1 s of log time, chunks of at most 100 ms: about ten chunks however small.
  const Written written = writeFile(
      path, {.compression = GetParam(), .chunk_bytes = 1 << 24, .chunk_span_ns = 100'000'000});
  EXPECT_EQ(written.chunks, 10U);
}

TEST_P(McapFile, AFileCutAnywhereReadsItsCompleteChunks) {
  const fs::path closed = scratch("closed.mcap");
  const fs::path path = scratch("crashed.mcap");
  const Written written =
      writeFile(closed, {.compression = GetParam(), .chunk_bytes = 4096}, &path);
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> whole{std::istreambuf_iterator<char>(in), {}};
  ASSERT_GT(written.chunks, 3U);
  // Every cut: the reader stops at the torn record and never reports a message it cannot have.
  std::uint64_t previous = 0;
  for (std::size_t cut = 8; cut <= whole.size(); cut += 97) {
    const fs::path cut_path = scratch("cut_part.mcap");
    std::ofstream(cut_path, std::ios::binary)
        .write(whole.data(), static_cast<std::streamsize>(cut));
    const McapContents contents = readMcap(cut_path.string());
    EXPECT_FALSE(contents.complete);
    EXPECT_FALSE(contents.stopped.empty());
    EXPECT_GE(contents.messages, previous);  // more file, never fewer messages
    EXPECT_LE(contents.chunks, written.chunks);
    previous = contents.messages;
    expectAllMessages(cut_path, contents.messages);  // the ones read are the first ones, intact
  }
  // The unclosed file itself (no summary, no footer) holds every message: the flush wrote them.
  const McapContents unclosed = readMcap(path.string());
  EXPECT_EQ(unclosed.messages, 1000U);
  EXPECT_EQ(unclosed.chunks, written.chunks);
  EXPECT_FALSE(unclosed.statistics.has_value());
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapFile,
                         ::testing::Values(Compression::kNone, Compression::kZstd),
                         [](const auto& test) {
                           return test.param == Compression::kZstd ? "zstd" : "none";
                         });

TEST(McapFileErrors, ADamagedChunkIsNamed) {
  const fs::path path = scratch("damaged.mcap");
  writeFile(path, {.compression = Compression::kNone, .chunk_bytes = 4096});
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekp(600);  // inside the first chunk's records
  file.put('\x55');
  file.close();
  try {
    readMcap(path.string());
    FAIL() << "a flipped byte went unnoticed";
  } catch (const McapError& error) {
    EXPECT_NE(std::string(error.what()).find("CRC"), std::string::npos) << error.what();
  }
}

TEST(McapFileErrors, NotMcapAndUnwritablePathsAreNamed) {
  const fs::path text = scratch("not.mcap");
  std::ofstream(text) << "hello\n";
  EXPECT_THROW(
      {
        try {
          readMcap(text.string());
        } catch (const McapError& error) {
          EXPECT_NE(std::string(error.what()).find("not an MCAP file"), std::string::npos);
          throw;
        }
      },
      McapError);
  EXPECT_THROW(
      {
        try {
          McapWriter writer("/nonexistent-folder/run.mcap", {});
        } catch (const McapError& error) {
          EXPECT_NE(std::string(error.what()).find("/nonexistent-folder/run.mcap"),
                    std::string::npos);
          // Named as the folder that is missing (none is made), before any file is tried.
          EXPECT_NE(
              std::string(error.what()).find("the folder '/nonexistent-folder' does not exist"),
              std::string::npos)
              << error.what();
          throw;
        }
      },
      McapError);
}

}  // namespace
}  // namespace comply::record
