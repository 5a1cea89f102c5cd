// The frames between a host and its transport process (src/transport/process/frames.hpp): cut
// anywhere by the socket, they come out whole and in order; a sample keeps its writer, its
// participant and what did not fit; a length no frame can have stops the stream.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "frames.hpp"

namespace comply::transport::process {
namespace {

Sample<CartesianCommandMessage> someSample() {
  Sample<CartesianCommandMessage> sample;
  sample.message.header = {{1700000000, 123456789}, "fr3_link0"};
  sample.message.command = CartesianCommand::zero(7);
  sample.message.command.fields = CommandField::kPosition | CommandField::kNullspace;
  sample.message.command.position = Eigen::Vector3d(0.4, -0.1, 0.5);
  sample.message.command.nullspace_stiffness.setConstant(12.5);
  sample.publisher = 0x1122334455667788ULL;
  sample.participant = 42;
  sample.sender = {0x01, 0x10, 0xaa, 0x55, 1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 1, 0xc1};
  sample.malformed = "torque_feedforward has 13 entries";
  sample.malformed_reason = Reason::kInvalidChunk;
  return sample;
}

TEST(TransportProcessFrames, ComeOutWholeHoweverTheStreamIsCut) {
  std::vector<std::uint8_t> stream;
  std::vector<std::uint8_t> scratch;
  appendFrame(FrameKind::kReady, std::string_view("topics rt/comply/*"), stream);
  appendSampleFrame(FrameKind::kCartesian, someSample(), scratch, stream);
  appendFrame(FrameKind::kDeparted, std::uint64_t{77}, stream);

  for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, stream.size()}) {
    FrameReader reader;
    std::vector<Frame> frames;
    for (std::size_t at = 0; at < stream.size(); at += piece) {
      reader.append({stream.data() + at, std::min(piece, stream.size() - at)});
      while (auto frame = reader.next()) {
        frames.push_back(std::move(*frame));
      }
    }
    ASSERT_EQ(frames.size(), 3U) << "pieces of " << piece;
    EXPECT_FALSE(reader.broken());
    EXPECT_EQ(frames[0].kind, FrameKind::kReady);
    EXPECT_EQ(readText(frames[0].payload), "topics rt/comply/*");
    ASSERT_EQ(frames[1].kind, FrameKind::kCartesian);
    Sample<CartesianCommandMessage> sample;
    ASSERT_TRUE(readSampleFrame(frames[1].payload, sample));
    const Sample<CartesianCommandMessage> sent = someSample();
    EXPECT_EQ(sample.publisher, sent.publisher);
    EXPECT_EQ(sample.participant, sent.participant);
    EXPECT_EQ(sample.sender, sent.sender);
    EXPECT_EQ(sample.malformed, sent.malformed);
    EXPECT_EQ(sample.malformed_reason, sent.malformed_reason);
    EXPECT_EQ(sample.message.header.stamp, sent.message.header.stamp);
    EXPECT_EQ(sample.message.header.frame_id, sent.message.header.frame_id);
    EXPECT_EQ(sample.message.command.fields, sent.message.command.fields);
    EXPECT_EQ(sample.message.command.position, sent.message.command.position);
    EXPECT_EQ(sample.message.command.nullspace_stiffness, sent.message.command.nullspace_stiffness);
    EXPECT_EQ(readU64(frames[2].payload), 77U);
  }
}

TEST(TransportProcessFrames, ASampleFrameCutShortIsRefused) {
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> scratch;
  appendSampleFrame(FrameKind::kCartesian, someSample(), scratch, frame);
  const std::span<const std::uint8_t> payload(frame.data() + 5, frame.size() - 5);
  for (std::size_t cut = 0; cut + 3 < payload.size(); cut += 5) {
    Sample<CartesianCommandMessage> sample;
    EXPECT_FALSE(readSampleFrame(payload.first(cut), sample)) << cut;
  }
  EXPECT_FALSE(readU64(payload.first(7)).has_value());
}

TEST(TransportProcessFrames, AMessageTooLargeForAFrameTravelsAsMalformed) {
  // A chunk whose frame_id every waypoint repeats: 64 x 300 kB, more than a frame may hold.
  Sample<CartesianChunkMessage> sample;
  sample.message.header = {{1700000000, 5}, std::string(300'000, 'x')};
  sample.message.chunk.fields = CommandField::kPosition;
  sample.message.chunk.waypoints.assign(64, {0.1, CartesianCommand::zero(7)});
  sample.publisher = 9;
  std::vector<std::uint8_t> scratch;
  std::vector<std::uint8_t> frame;
  appendSampleFrame(FrameKind::kCartesianChunk, sample, scratch, frame);
  ASSERT_LT(frame.size(), 4096U);
  FrameReader reader;
  reader.append(frame);
  const auto read = reader.next();
  ASSERT_TRUE(read.has_value());
  Sample<CartesianChunkMessage> received;
  ASSERT_TRUE(readSampleFrame(read->payload, received));
  EXPECT_EQ(received.publisher, 9U);
  EXPECT_EQ(received.message.header.stamp, sample.message.header.stamp);  // still accounted
  EXPECT_NE(received.malformed.find("more than a comply message can be"), std::string::npos)
      << received.malformed;
  EXPECT_EQ(received.malformed_reason, Reason::kTooLarge);
}

TEST(TransportProcessFrames, ALengthNoFrameCanHaveStopsTheStream) {
  for (const std::uint32_t length : {std::uint32_t{0}, std::uint32_t(kMaxFrameBytes + 1)}) {
    FrameReader reader;
    std::vector<std::uint8_t> bytes(4);
    std::memcpy(bytes.data(), &length, sizeof(length));
    bytes.push_back(static_cast<std::uint8_t>(FrameKind::kHeartbeat));
    reader.append(bytes);
    EXPECT_FALSE(reader.next().has_value());
    EXPECT_TRUE(reader.broken()) << length;
  }
}

}  // namespace
}  // namespace comply::transport::process
