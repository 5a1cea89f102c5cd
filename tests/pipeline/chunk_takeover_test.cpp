// What the chunk player tells a policy: predict() against what play() writes, cycle by cycle,
// across a blend, a takeover time and a chunk that runs out; the takeover rules (a chunk waits for
// its time, a newer one supersedes it, stop() drops it); and each chunk's timing record (the
// waypoints already past, the seam's jump, starvation), against numbers worked out by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "comply/pipeline/chunk_player.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

constexpr int kDof = 7;
constexpr double kPeriod_s = 0.001;
using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;

/// Joint chunk along joint 0: waypoint k at `first_s` + k `step_s`, at q0 = `curve`(its time).
template <typename Curve>
JointChunk jointChunk(int count, double first_s, double step_s, Curve curve) {
  JointChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kStiffness;
  for (int k = 0; k < count; ++k) {
    JointCommand command = JointCommand::zero(kDof);
    const double t = first_s + k * step_s;
    command.position[0] = curve(t);
    command.stiffness = JointVector::Constant(kDof, 100.0 + 10.0 * k);
    chunk.waypoints.push_back({t, command});
  }
  return chunk;
}

double sway(double t) {
  return 0.3 * std::sin(2.0 * t) + 0.1 * t;
}
double otherSway(double t) {
  return 0.3 * std::sin(2.0 * t) + 0.1 * t + 0.002 * std::cos(9.0 * t);
}

CommandBus restBus() {
  return schema::toBus(JointCommand::zero(kDof), kDof);
}

/// A cycle as the controller runs it: a waiting chunk's takeover, then the running chunk.
void cycle(ChunkPlayer& player, double now_s, CommandBus& active) {
  player.clearEvents();
  (void)player.takeOverDue(now_s, active);
  (void)player.play(now_s, active);
}

const Joint& joint(const CommandBus& bus) {
  return std::get<Joint>(bus);
}

TEST(ChunkPrediction, MatchesWhatTheCycleWritesAcrossABlendATakeoverAndTheEnd) {
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.1);
  CommandBus active = restBus();
  double now_s = 0.0;
  // The first chunk from rest; the second planned on an observation at 0.2005 s, taking over at
  // its waypoint 3 (0.3005 s), between two cycles: the cycle at 0.301 s takes it over.
  const int first = player.load(jointChunk(16, 0.0, 1.0 / 30.0, sway), 0.0, 1);
  ASSERT_TRUE(player.take(first, active, now_s));
  for (int k = 0; k < 150; ++k) {
    now_s += kPeriod_s;
    cycle(player, now_s, active);
  }
  JointChunk second = jointChunk(16, 0.2005, 1.0 / 30.0, otherSway);
  second.takeover_s = second.waypoints[3].time_s;
  const int slot = player.load(second, 0.0, 2);
  ASSERT_GE(slot, 0);
  EXPECT_FALSE(player.take(slot, active, now_s)) << "its takeover is ahead: it waits";
  ASSERT_TRUE(player.waiting());

  // From here to past the second chunk's end (0.7 s), no new chunk: the prediction made now
  // must be what the cycles write.
  std::vector<double> times;
  for (int k = 1; k <= 700; ++k) {
    times.push_back(now_s + k * kPeriod_s);
  }
  std::vector<CommandBus> predicted(times.size(), active);
  ASSERT_TRUE(player.predict(times, now_s, kPeriod_s, predicted));
  for (std::size_t k = 0; k < times.size(); ++k) {
    now_s += kPeriod_s;
    cycle(player, now_s, active);
    for (int j = 0; j < kDof; ++j) {
      ASSERT_NEAR(joint(predicted[k]).position[j], joint(active).position[j], 1e-12) << k;
      ASSERT_NEAR(joint(predicted[k]).velocity[j], joint(active).velocity[j], 1e-10) << k;
      ASSERT_NEAR(joint(predicted[k]).stiffness[j], joint(active).stiffness[j], 1e-9) << k;
    }
  }
  EXPECT_FALSE(player.playing()) << "the second chunk ran out at 0.7 s";
}

TEST(ChunkPrediction, AnswersTimesAlreadyPastFromTheChunkThatPlayedThen) {
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.1);
  CommandBus active = restBus();
  double now_s = 0.0;
  ASSERT_TRUE(player.take(player.load(jointChunk(16, 0.0, 0.05, sway), 0.0, 1), active, now_s));
  std::vector<double> written;  // joint 0 at each cycle
  for (int k = 0; k < 100; ++k) {
    now_s += kPeriod_s;
    cycle(player, now_s, active);
    written.push_back(joint(active).position[0]);
  }
  ASSERT_TRUE(
      player.take(player.load(jointChunk(16, 0.1, 0.05, otherSway), 0.0, 2), active, now_s));
  // 20 cycles back: before the second chunk took over, from the first one's slot.
  const std::vector<double> times{now_s - 20 * kPeriod_s, now_s - 5 * kPeriod_s};
  std::vector<CommandBus> predicted(times.size(), active);
  ASSERT_TRUE(player.predict(times, now_s, kPeriod_s, predicted));
  EXPECT_NEAR(joint(predicted[0]).position[0], written[written.size() - 21], 1e-12);
  EXPECT_NEAR(joint(predicted[1]).position[0], written[written.size() - 6], 1e-12);

  // Once the first chunk's slot holds another chunk, those times are not known any more.
  for (int k = 0; k < 3; ++k) {
    (void)player.load(jointChunk(4, 0.5, 0.05, sway), 0.0, 3 + k);
  }
  std::vector<CommandBus> again(times.size(), active);
  EXPECT_FALSE(player.predict(times, now_s, kPeriod_s, again));
  EXPECT_TRUE(std::isnan(joint(again[0]).position[0]));
}

TEST(ChunkTakeover, ANewerChunkSupersedesAWaitingOneAndStopDropsIt) {
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.05);
  CommandBus active = restBus();
  ASSERT_TRUE(player.take(player.load(jointChunk(16, 0.0, 0.05, sway), 0.0, 1), active, 0.0));
  JointChunk waiting = jointChunk(8, 0.1, 0.05, sway);
  waiting.takeover_s = 0.2;
  player.clearEvents();
  EXPECT_FALSE(player.take(player.load(waiting, 0.0, 2), active, 0.01));
  EXPECT_TRUE(player.events().empty());
  EXPECT_FALSE(player.take(player.load(waiting, 0.0, 3), active, 0.02));
  ASSERT_EQ(player.events().size(), 1U);
  EXPECT_EQ(player.events()[0].sequence, 2U);
  EXPECT_EQ(player.events()[0].end, ChunkEnd::kSuperseded);
  EXPECT_TRUE(std::isnan(player.events()[0].takeover_s));

  player.clearEvents();
  EXPECT_EQ(player.takeOverDue(0.19, active), 0U) << "not before its time";
  EXPECT_EQ(player.takeOverDue(0.2 - 0.5e-9, active), 3U) << "a nanosecond's tolerance";
  ASSERT_EQ(player.events().size(), 1U);
  EXPECT_EQ(player.events()[0].end, ChunkEnd::kTookOver);

  EXPECT_FALSE(player.take(player.load(waiting, 0.0, 4), active, 0.0));
  player.clearEvents();
  player.stop();
  ASSERT_EQ(player.events().size(), 1U);
  EXPECT_EQ(player.events()[0].sequence, 4U);
  EXPECT_EQ(player.events()[0].end, ChunkEnd::kDropped);
  EXPECT_FALSE(player.waiting());
  EXPECT_FALSE(player.playing());
}

TEST(ChunkTiming, CountsTheWaypointsPastAndMeasuresTheSeam) {
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.1);
  CommandBus active = restBus();
  JointChunk chunk = jointChunk(10, 0.0, 0.02, [](double t) { return 0.5 * t; });
  chunk.observation_s = 0.0;
  // Taken at 0.0405 s: waypoints at 0, 0.02 and 0.04 are past; the one at 0.06 is not.
  player.clearEvents();
  ASSERT_TRUE(player.take(player.load(chunk, 0.0, 7, 0.039), active, 0.0405));
  ASSERT_EQ(player.events().size(), 1U);
  const ChunkTiming& timing = player.events()[0];
  EXPECT_EQ(timing.sequence, 7U);
  EXPECT_EQ(timing.waypoints, 10);
  EXPECT_EQ(timing.waypoints_past, 3);
  EXPECT_DOUBLE_EQ(timing.takeover_s, 0.0405);
  EXPECT_DOUBLE_EQ(timing.received_s, 0.039);
  EXPECT_DOUBLE_EQ(timing.observation_s, 0.0);
  EXPECT_DOUBLE_EQ(timing.first_waypoint_s, 0.0);
  EXPECT_DOUBLE_EQ(timing.last_waypoint_s, 0.18);
  // From rest at q0 = 0 onto a line 0.5 t: the jump is the line's value and speed there.
  EXPECT_NEAR(timing.position_jump, 0.5 * 0.0405, 1e-12);
  EXPECT_NEAR(timing.velocity_jump, 0.5, 1e-12);
  EXPECT_FALSE(timing.starved);

  // A waypoint exactly at the takeover (up to rounding) is the one the cycle reaches, not past.
  ChunkPlayer exact(COMPLY_COMMAND_JOINT, kDof, 0.1);
  CommandBus at_rest = restBus();
  JointChunk on_grid = jointChunk(10, 0.0, 0.02, [](double t) { return 0.5 * t; });
  exact.clearEvents();
  ASSERT_TRUE(exact.take(exact.load(on_grid, 0.0, 1), at_rest, 0.1 * 0.4 + 1e-17));
  EXPECT_EQ(exact.events()[0].waypoints_past, 2);
}

TEST(ChunkTiming, SaysWhenTheArmCameToRestWaitingForTheNextChunk) {
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.0);
  CommandBus active = restBus();
  ASSERT_TRUE(player.take(player.load(jointChunk(3, 0.0, 0.01, sway), 0.0, 1), active, 0.0));
  double now_s = 0.0;
  while (player.playing()) {
    now_s += kPeriod_s;
    cycle(player, now_s, active);
  }
  const double ran_out_s = now_s;
  EXPECT_NEAR(ran_out_s, 0.02, 1e-9);
  player.clearEvents();
  ASSERT_TRUE(player.take(player.load(jointChunk(3, 0.05, 0.01, sway), 0.0, 2), active, 0.045));
  ASSERT_EQ(player.events().size(), 1U);
  EXPECT_TRUE(player.events()[0].starved);
  EXPECT_NEAR(player.events()[0].rest_s, 0.045 - ran_out_s, 1e-12);

  // A chunk that takes over from a running one did not starve.
  player.clearEvents();
  ASSERT_TRUE(player.take(player.load(jointChunk(3, 0.05, 0.01, sway), 0.0, 3), active, 0.046));
  EXPECT_FALSE(player.events()[0].starved);
}

}  // namespace
}  // namespace comply::pipeline
