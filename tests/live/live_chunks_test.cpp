// Timed chunks on the live host, over DDS and in process alike: a chunk's waypoints are played on
// the host's clock (the wall clock, which the chunk's times are on) to its last one; a late chunk
// is refused as late_chunk; one sender's commands and chunks pass the publisher rule together.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

using namespace std::chrono_literals;

TEST_P(LiveHostOn, PlaysAChunkOnTheHostsClockAndRefusesALateOne) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("chunks", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.connectChunks(1));

  const double now_s = transport::Stamp::now().seconds();
  const transport::CartesianChunkMessage chunk = chunkAlongY(*state, now_s + 0.1, 0.05, 8);
  ASSERT_TRUE(host.send(chunk, 1));
  const std::int64_t stamp = chunk.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }));
  ASSERT_EQ(host.outcomes()[stamp].front().outcome, transport::Outcome::kApplied)
      << host.outcomes()[stamp].front().message;

  // The last waypoint is due 0.45 s after now_s: the reference is on it soon after, and stays.
  const double last_y = chunk.chunk.waypoints.back().command.position.y();
  std::this_thread::sleep_until(std::chrono::system_clock::time_point(
      std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::duration<double>(now_s + 0.7))));
  const auto after = host.state(2s);
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->reference_position[1], last_y, 1e-9);
  EXPECT_NEAR(after->tcp_position[1], last_y, 0.01) << "the arm followed the chunk";

  // A chunk whose last waypoint is past, and a command from the same sender: the one refused
  // with its reason, the other applied (one sender, whatever topic it writes).
  const double late_s = transport::Stamp::now().seconds() - 1.0;
  const transport::CartesianChunkMessage late = chunkAlongY(*after, late_s, 0.05, 4);
  ASSERT_TRUE(host.send(late, 1));
  transport::CartesianCommandMessage command;
  command.header.stamp = transport::Stamp::now();
  command.command = CartesianCommand::zero(static_cast<int>(state->position.size()));
  command.command.fields = CommandField::kNone;
  ASSERT_TRUE(host.send(command, 1));
  const std::int64_t late_stamp = late.header.stamp.nanoseconds();
  const std::int64_t command_stamp = command.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) {
    return host.outcomes().count(late_stamp) > 0 && host.outcomes().count(command_stamp) > 0;
  }));
  const transport::CommandOutcomeMessage& refused = host.outcomes()[late_stamp].front();
  EXPECT_EQ(refused.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(refused.reason, transport::Reason::kLateChunk);
  EXPECT_NE(refused.message.find("last waypoint was due"), std::string::npos) << refused.message;
  EXPECT_EQ(host.outcomes()[command_stamp].front().outcome, transport::Outcome::kApplied);
}

/// A chunk waiting for its start (its first waypoint still ahead) whose sender then leaves: the
/// red team's chunk 5 s ahead left every other sender's commands without an outcome until its
/// time. Another sender's commands are applied at once, and the waiting chunk is released (the
/// reference does not move to it when its time comes).
TEST_P(LiveHostOn, AChunkWaitingForItsStartDoesNotHoldAnotherSendersCommands) {
  HostHarness& host = *host_;
  // A lead limit of 6 s (validation.max_stamp_lead_s) and a chunk 4 s ahead: ample time for a
  // second sender's discovery on a busy machine before the chunk's time comes.
  host.setConfigFile(
      hostConfigWith("waiting.yaml", "    validation:\n      max_stamp_lead_s: 6.0\n"));
  const auto state = host.startConnected("waiting", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.connectChunks(1));

  // 4 s ahead, 3.5 cm along y.
  constexpr double kLeadS = 4.0;
  const double now_s = transport::Stamp::now().seconds();
  const transport::CartesianChunkMessage chunk = chunkAlongY(*state, now_s + kLeadS, 0.05, 8);
  ASSERT_TRUE(host.send(chunk, 1));
  const std::int64_t stamp = chunk.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }));
  ASSERT_EQ(host.outcomes()[stamp].front().outcome, transport::Outcome::kApplied)
      << host.outcomes()[stamp].front().message;

  host.close(1);
  // A second sender, connected after the first left: its probes (commands with no field group,
  // which leave a chunk playing) are accounted while the chunk would still wait.
  ASSERT_TRUE(host.connect(2, static_cast<int>(state->position.size())));
  EXPECT_LT(transport::Stamp::now().seconds(), now_s + kLeadS)
      << "accounted only once the waiting chunk's time had come";

  // After the chunk's last waypoint: the reference did not move to the departed sender's chunk.
  std::this_thread::sleep_until(std::chrono::system_clock::time_point(
      std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::duration<double>(now_s + kLeadS + 0.7))));
  const auto after = host.state(2s);
  ASSERT_TRUE(after);
  // It was dropped where the blend toward its lead-in (2.5 mm behind its first waypoint) had got;
  // played, it would have gone 35 mm.
  EXPECT_NEAR(after->reference_position[1], state->reference_position[1], 0.003)
      << "the departed sender's chunk played";
  const transport::Stamp command_stamp = transport::Stamp::now();
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), command_stamp), 2));
  ASSERT_TRUE(host.poll(
      5s, [&](const auto&) { return host.outcomes().count(command_stamp.nanoseconds()) > 0; }));
  const transport::CommandOutcomeMessage& outcome =
      host.outcomes()[command_stamp.nanoseconds()].front();
  EXPECT_EQ(outcome.outcome, transport::Outcome::kApplied) << outcome.message;
}

/// A chunk planned on an observation that keeps the running chunk until its waypoint 3: its
/// outcome, applied when it took over, carries its timing record on the host's clock: the
/// observation and takeover it asked for, when it took over (at waypoint 3's time when it arrived
/// before it, else in the cycle it arrived in), and the waypoints already past then.
TEST_P(LiveHostOn, AChunksOutcomeCarriesItsTakeoverTiming) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("chunk_timing", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.connectChunks(1));

  // A 1.5 s chunk that takes over at once, planned on an observation 10 ms ago.
  const double start_s = transport::Stamp::now().seconds() + 0.05;
  transport::CartesianChunkMessage running = chunkOnLine(*state, start_s, start_s, 0.05, 30);
  running.chunk.observation_s = start_s - 0.06;
  ASSERT_TRUE(host.send(running, 1));
  const std::int64_t running_stamp = running.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(running_stamp) > 0; }));
  const transport::CommandOutcomeMessage first = host.outcomes()[running_stamp].front();
  ASSERT_EQ(first.outcome, transport::Outcome::kApplied) << first.message;
  ASSERT_EQ(first.chunk.size(), 1U) << "the outcome of a chunk that took over has its record";
  EXPECT_EQ(first.chunk[0].end, transport::ChunkEnd::kTookOver);
  EXPECT_EQ(first.chunk[0].sequence, first.sequence_number);
  EXPECT_EQ(first.chunk[0].requested_takeover, transport::Stamp{}) << "at once: none asked";
  EXPECT_EQ(first.chunk[0].waypoints, 30U);

  // The next one, planned on the observation now, its waypoint 0 there, 10 waypoints 50 ms apart
  // on the same line; it keeps the running chunk until its waypoint 3.
  constexpr int kKeep = 3;
  constexpr double kSpacingS = 0.05;
  const double observation_s = transport::Stamp::now().seconds();
  transport::CartesianChunkMessage next =
      chunkOnLine(*state, start_s, observation_s, kSpacingS, 10);
  next.chunk.observation_s = observation_s;
  next.chunk.takeover_s = next.chunk.waypoints[kKeep].time_s;
  ASSERT_TRUE(host.send(next, 1));
  const std::int64_t stamp = next.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }));
  const transport::CommandOutcomeMessage& outcome = host.outcomes()[stamp].front();
  ASSERT_EQ(outcome.outcome, transport::Outcome::kApplied) << outcome.message;
  ASSERT_EQ(outcome.chunk.size(), 1U);
  const transport::ChunkTimingMessage& timing = outcome.chunk[0];
  EXPECT_EQ(timing.end, transport::ChunkEnd::kTookOver);
  EXPECT_EQ(timing.sequence, outcome.sequence_number);
  EXPECT_EQ(timing.takeover_cycle, outcome.cycle) << "taken over in the cycle that applied it";
  EXPECT_EQ(timing.waypoints, 10U);
  // One offset maps the record's times onto the host's clock: their differences are the chunk's.
  const double observed_s = transport::secondsOrNaN(timing.observation);
  const double first_s = transport::secondsOrNaN(timing.first_waypoint);
  const double requested_s = transport::secondsOrNaN(timing.requested_takeover);
  const double takeover_s = transport::secondsOrNaN(timing.takeover);
  EXPECT_NEAR(observed_s, observation_s, 0.25) << "on the host's (wall) clock";
  EXPECT_NEAR(first_s - observed_s, 0.0, 1e-6);
  EXPECT_NEAR(requested_s - first_s, kKeep * kSpacingS, 1e-6);
  EXPECT_NEAR(transport::secondsOrNaN(timing.last_waypoint) - first_s, 9 * kSpacingS, 1e-6);
  EXPECT_GE(takeover_s, requested_s - 1e-6) << "not before the takeover it asked for";
  EXPECT_GE(timing.waypoints_past, static_cast<std::uint32_t>(kKeep));
  // The waypoints before its takeover are the ones counted past.
  std::uint32_t before = 0;
  std::uint32_t at_most = 0;
  for (int k = 0; k < 10; ++k) {
    before += first_s + k * kSpacingS < takeover_s - 1e-6 ? 1U : 0U;
    at_most += first_s + k * kSpacingS < takeover_s + 1e-6 ? 1U : 0U;
  }
  EXPECT_GE(timing.waypoints_past, before);
  EXPECT_LE(timing.waypoints_past, at_most);
}

// `comply send --file` with chunks among commands: each chunk's times are seconds after it is
// sent; commands and chunks are all applied, and the arm ends on the last chunk's last waypoint.
TEST(LiveHost, CommandSendSendsChunksFromAFile) {
  ProcessHost live("chunkfile");
  const auto state = live.client.state(20s);
  ASSERT_TRUE(state);
  const std::string file = scratchFile("send_chunks.jsonl");
  const double x = state->reference_position[0];
  const double y = state->reference_position[1];
  const double z = state->reference_position[2];
  {
    std::ofstream lines(file);
    lines << "{\"position\": [" << x << ", " << y << ", " << z << "]}\n";
    for (int c = 0; c < 3; ++c) {  // three chunks, each 2 cm further along y over 0.4 s
      lines << "{\"chunk\": [";
      for (int k = 0; k <= 4; ++k) {
        lines << (k > 0 ? ", " : "") << "{\"time\": " << 0.1 * k << ", \"position\": [" << x << ", "
              << y + 0.02 * c + 0.005 * k << ", " << z << "]"
              << (k == 0 ? ", \"stiffness_translational\": 800" : "") << "}";
      }
      lines << "]}\n";
    }
  }
  const SendResult sent = sendFile(live.domain, "chunkfile", file, "2");
  EXPECT_EQ(sent.exit_code, 0);
  EXPECT_EQ(sent.applied, 4U) << sent.text;
  std::this_thread::sleep_for(600ms);  // the last chunk runs 0.4 s after it was sent
  const auto after = live.client.state(2s);
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->reference_position[1], y + 0.06, 1e-6);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace comply::live_test
