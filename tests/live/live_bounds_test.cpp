// What no command may carry is answered, over DDS and in process alike, with its outcome: a chunk
// of more waypoints than a chunk may carry (the wire's bound of 64 once had DDS refuse the sample,
// so the sender never heard of it), and a header.frame_id longer than a frame's name can be
// (megabytes of it were applied, and the host and its transport kept the memory). Neither
// changes the command in force.

#include <gtest/gtest.h>

#include <thread>

#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

using namespace std::chrono_literals;

TEST_P(LiveHostOn, AChunkOfMoreWaypointsThanAllowedIsAnsweredAsInvalid) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("long_chunk", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.connectChunks(1));

  const transport::CartesianChunkMessage chunk =
      chunkAlongY(*state, transport::Stamp::now().seconds() + 0.1, 0.01, 65, 1e-4);
  ASSERT_TRUE(host.send(chunk, 1)) << "the sender's transport refused the chunk";
  const std::int64_t stamp = chunk.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }))
      << "no outcome for a chunk of 65 waypoints";
  const transport::CommandOutcomeMessage& outcome = host.outcomes()[stamp].front();
  EXPECT_EQ(outcome.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(toString(outcome.reason), "invalid_chunk") << outcome.message;
  EXPECT_NE(outcome.message.find("1 to 64 waypoints, this one 65"), std::string::npos)
      << outcome.message;
}

TEST_P(LiveHostOn, AFrameIdLongerThanAllowedIsRefusedAndChangesNothing) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("frame_id", 1);
  ASSERT_TRUE(state);
  const transport::Stamp first = transport::Stamp::now();
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), first), 1));
  ASSERT_TRUE(
      host.poll(5s, [&](const auto&) { return host.outcomes().count(first.nanoseconds()) > 0; }));
  ASSERT_EQ(host.outcomes()[first.nanoseconds()].front().outcome, transport::Outcome::kApplied);
  std::optional<transport::ControllerStateMessage> in_force;
  for (int attempt = 0; attempt < 100 && !(in_force && in_force->reference_stamp == first);
       ++attempt) {
    in_force = host.state(100ms);
  }
  ASSERT_TRUE(in_force && in_force->reference_stamp == first) << "the first command never applied";

  // A megabyte of frame_id on a command that would move the reference by 1 cm.
  transport::CartesianCommandMessage large =
      poseCommand(*state, Eigen::Vector3d(0.0, 0.01, 0.0),
                  transport::Stamp::fromNanoseconds(first.nanoseconds() + 1'000'000));
  large.header.frame_id = std::string(std::size_t{1} << 20U, 'x');
  ASSERT_TRUE(host.send(large, 1));
  const std::int64_t stamp = large.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }));
  const transport::CommandOutcomeMessage& outcome = host.outcomes()[stamp].front();
  EXPECT_EQ(outcome.outcome, transport::Outcome::kRejected) << "a 1 MB frame_id was applied";
  EXPECT_EQ(toString(outcome.reason), "too_large") << outcome.message;
  EXPECT_NE(outcome.message.find("header.frame_id is 1048576 bytes"), std::string::npos)
      << outcome.message;
  EXPECT_NE(outcome.message.find("256"), std::string::npos) << outcome.message;

  // The newest state a while after the refusal (a cycle would have taken the command by then).
  std::optional<transport::ControllerStateMessage> after;
  for (const auto until = Clock::now() + 300ms; Clock::now() < until;) {
    if (auto newest = host.state(100ms)) {
      after = std::move(newest);
    }
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_TRUE(after);
  EXPECT_EQ(after->reference_stamp, first);
  EXPECT_EQ(after->reference_sequence, in_force->reference_sequence);
  EXPECT_EQ(after->reference_position, in_force->reference_position);
}

}  // namespace
}  // namespace comply::live_test
