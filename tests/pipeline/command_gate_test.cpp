// The command gate's rules, one at a time, with a real joint wrapper behind it where the wrapper's
// own verdict matters (queue full) and a scripted verdict elsewhere. Every host (comply run, the
// ROS 2 controllers, Python's Sim) takes its commands through this class.

#include "comply/pipeline/command_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline {
namespace {

using namespace test;  // the FR3 wrapper fixtures

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::uint64_t kWriterA = 0xA;
constexpr std::uint64_t kWriterB = 0xB;

/// A Cartesian command from `publisher` stamped `stamp_ns`, offered at steady time `now_ns`.
Offer offerAt(std::int64_t stamp_ns, std::uint64_t publisher = kWriterA, std::int64_t now_ns = 0) {
  Offer offer;
  offer.stamp_ns = stamp_ns;
  offer.kind = CommandKind::kCartesian;
  offer.publisher = publisher;
  offer.now_ns = now_ns;
  return offer;
}

/// The gate's own rules, with a scripted wrapper verdict: accepted commands are numbered as a
/// wrapper numbers them.
class CommandGateTest : public ::testing::Test {
 protected:
  /// The verdict of a wrapper that accepts: the next number.
  Verdict accepted() { return {.sequence = ++sequence_}; }
  /// Offers a command the wrapper would accept; the outcome settled by it, if any.
  std::vector<CommandOutcome> offer(const Offer& offer, bool active = true) {
    gate_.offer(offer, active, [this](std::int64_t) { return accepted(); });
    return gate_.takeOutcomes();
  }
  /// The cycle `cycle` ran with the command numbered `sequence` in force.
  bool noteCycle(std::uint64_t cycle, std::uint64_t sequence, std::int64_t wall_ns) {
    return gate_.noteCycle(cycle, CommandId{.sequence = sequence}, [wall_ns] { return wall_ns; });
  }

  CommandGate gate_{{.kind = CommandKind::kCartesian, .publisher_timeout_s = 0.5}};
  std::uint64_t sequence_ = 0;
};

/// A chunk's timing record reaches its outcome when it was noted before the cycle that settles it
/// (a chunk that took over), or while the outcome waits (one superseded while it waited); one
/// noted after its outcome went is not attached to another's. Its times go onto the host's
/// clock with the offset of its cycle.
TEST_F(CommandGateTest, AChunksOutcomeCarriesTheTimingRecordNotedBeforeItsCycle) {
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(offer(offerAt((9 + k) * kSecond)).empty());  // numbers 1, 2, 3
  }
  ChunkTiming took_over;
  took_over.sequence = 1;
  took_over.takeover_s = 2.5;
  took_over.observation_s = 2.4;
  took_over.waypoints_past = 3;
  ASSERT_TRUE(gate_.noteChunk(40, took_over, 2.5, 7 * kSecond));
  ASSERT_TRUE(noteCycle(40, 1, 7 * kSecond));
  ChunkTiming superseded;
  superseded.sequence = 2;
  superseded.end = ChunkEnd::kSuperseded;
  ASSERT_TRUE(gate_.noteChunk(41, superseded, 2.501, 7 * kSecond + 1'000'000));
  gate_.settle();
  std::vector<CommandOutcome> outcomes = gate_.takeOutcomes();
  ASSERT_EQ(outcomes.size(), 1U);
  ASSERT_TRUE(outcomes[0].chunk.has_value()) << "settled in the cycle its record came in";
  EXPECT_EQ(outcomes[0].chunk->timing.waypoints_past, 3);
  EXPECT_EQ(outcomes[0].chunk->cycle, 40U);
  EXPECT_EQ(outcomes[0].chunk->hostNs(2.4), 7 * kSecond - 100'000'000);
  EXPECT_FALSE(outcomes[0].chunk->hostNs(took_over.requested_takeover_s)) << "NaN: none";

  ChunkTiming late = took_over;  // number 1's outcome has gone
  ASSERT_TRUE(gate_.noteChunk(42, late, 2.502, 7 * kSecond + 2'000'000));
  ASSERT_TRUE(noteCycle(42, 3, 7 * kSecond + 2'000'000));
  gate_.settle();
  outcomes = gate_.takeOutcomes();
  ASSERT_EQ(outcomes.size(), 2U);
  ASSERT_TRUE(outcomes[0].chunk.has_value())
      << "the superseded one's record, noted while it waited";
  EXPECT_EQ(outcomes[0].chunk->timing.end, ChunkEnd::kSuperseded);
  EXPECT_EQ(outcomes[0].sequence, 2U);
  EXPECT_FALSE(outcomes[1].chunk.has_value()) << "number 3 had no record";
}

TEST_F(CommandGateTest, AcceptedCommandsWaitForTheCycleThatTakesThem) {
  EXPECT_EQ(gate_.offer(offerAt(9 * kSecond), true, [this](std::int64_t) { return accepted(); }),
            CommandReason::kNone);
  EXPECT_TRUE(gate_.takeOutcomes().empty()) << "an accepted command is not settled yet";
  ASSERT_TRUE(noteCycle(40, 1, 122));
  gate_.settle();
  ASSERT_EQ(gate_.takeOutcomes().size(), 1U);
  EXPECT_TRUE(offer(offerAt(10 * kSecond)).empty());
  EXPECT_TRUE(offer(offerAt(11 * kSecond)).empty());
  EXPECT_EQ(gate_.pending(), 2U);

  // The cycle 41 took the first one only (the command in force is number 2).
  ASSERT_TRUE(noteCycle(41, 2, 123));
  gate_.settle();
  std::vector<CommandOutcome> outcomes = gate_.takeOutcomes();
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_TRUE(outcomes[0].applied);
  EXPECT_EQ(outcomes[0].stamp_ns, 10 * kSecond);
  EXPECT_EQ(outcomes[0].sequence, 2U);
  EXPECT_EQ(outcomes[0].cycle, 41U);
  EXPECT_EQ(outcomes[0].applied_ns, 123);
  EXPECT_EQ(outcomes[0].reason, CommandReason::kNone);
  EXPECT_GT(outcomes[0].received_ns, 0);
  EXPECT_EQ(gate_.counts().applied, 2U);

  // The same command in force again settles nothing and reads no clock (most cycles take no
  // command); the next number settles the second command.
  int clock_reads = 0;
  ASSERT_TRUE(gate_.noteCycle(42, CommandId{.sequence = 2}, [&] {
    ++clock_reads;
    return std::int64_t{124};
  }));
  EXPECT_EQ(clock_reads, 0);
  gate_.settle();
  EXPECT_TRUE(gate_.takeOutcomes().empty());
  ASSERT_TRUE(noteCycle(43, 3, 125));
  gate_.settle();
  outcomes = gate_.takeOutcomes();
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_EQ(outcomes[0].cycle, 43U);
  EXPECT_EQ(outcomes[0].sequence, 3U);
  EXPECT_EQ(gate_.counts().applied, 3U);
  EXPECT_EQ(gate_.pending(), 0U);
}

// Diagnostics.last_rejection: the newest refusal, the wrapper's or the gate's own, named by its
// reason, kept until the next.
TEST_F(CommandGateTest, TheLastRejectionIsTheNewestRefusalNamedByItsReason) {
  EXPECT_TRUE(offer(offerAt(5 * kSecond)).empty());
  EXPECT_EQ(gate_.counts().last_rejection, "");
  gate_.offer(offerAt(7 * kSecond), true, [](std::int64_t) {
    return Verdict{false, RejectionReason::kPoseJump, "pose_jump: target 2 m away"};
  });
  EXPECT_EQ(gate_.counts().last_rejection, "pose_jump: target 2 m away");
  gate_.offer(offerAt(8 * kSecond), true, [](std::int64_t) {
    return Verdict{false, RejectionReason::kNonFinite, "stamp"};
  });
  EXPECT_EQ(gate_.counts().last_rejection, "non_finite: stamp") << "named by its reason";
  EXPECT_EQ(gate_.offer(offerAt(9 * kSecond), true, [this](std::int64_t) { return accepted(); }),
            CommandReason::kNone);
  EXPECT_EQ(gate_.counts().last_rejection, "non_finite: stamp") << "kept";

  // Requests: another process's, while A holds the topics, and one the host could not carry out.
  std::string why;
  EXPECT_FALSE(gate_.admitRequest(/*participant=*/99, 0, why));
  EXPECT_EQ(gate_.counts().last_rejection, "other_publisher: " + why);
  gate_.noteRefusal("tare: no wrist sensor reading yet");
  EXPECT_EQ(gate_.counts().last_rejection, "tare: no wrist sensor reading yet");
}

TEST_F(CommandGateTest, ASecondPublisherIsRefusedUntilTheFirstIsSilent) {
  EXPECT_TRUE(offer(offerAt(1 * kSecond, kWriterA, 0)).empty());
  EXPECT_EQ(gate_.publisher(), kWriterA);
  std::vector<CommandOutcome> refused = offer(offerAt(2 * kSecond, kWriterB, kSecond / 10));
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0].reason, CommandReason::kOtherPublisher);
  EXPECT_NE(refused[0].message.find("holds the command topics"), std::string::npos);
  // The holder keeps the topics while it speaks...
  EXPECT_TRUE(offer(offerAt(3 * kSecond, kWriterA, kSecond / 5)).empty());
  EXPECT_EQ(offer(offerAt(4 * kSecond, kWriterB, kSecond / 2)).size(), 1U);
  // ...and loses them after 0.5 s of silence.
  EXPECT_TRUE(offer(offerAt(5 * kSecond, kWriterB, kSecond)).empty());
  EXPECT_EQ(gate_.publisher(), kWriterB);
  EXPECT_EQ(offer(offerAt(6 * kSecond, kWriterA, kSecond + 1)).size(), 1U);
}

TEST_F(CommandGateTest, TheWritersOfOneSendingProcessAreOneSender) {
  // A client's command writer and chunk writer: two writers, one participant.
  constexpr std::uint64_t kClient = 77;
  constexpr std::uint64_t kOtherProcess = 78;
  Offer command = offerAt(1 * kSecond, kWriterA, 0);
  command.participant = kClient;
  EXPECT_TRUE(offer(command).empty());
  Offer chunk = offerAt(2 * kSecond, kWriterB, kSecond / 10);
  chunk.participant = kClient;
  EXPECT_TRUE(offer(chunk).empty()) << "the chunk writer of the holder's process";
  Offer stranger = offerAt(3 * kSecond, kWriterB + 1, kSecond / 5);
  stranger.participant = kOtherProcess;
  const std::vector<CommandOutcome> refused = offer(stranger);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0].reason, CommandReason::kOtherPublisher);
}

TEST_F(CommandGateTest, WrongKindMalformedAndInactiveAreRefusedBeforeTheWrapperIsAsked) {
  int asked = 0;
  const auto submit = [&](std::int64_t) {
    ++asked;
    return accepted();
  };
  Offer joint = offerAt(1 * kSecond);
  joint.kind = CommandKind::kJoint;
  EXPECT_EQ(gate_.offer(joint, true, submit), CommandReason::kWrongKind);
  Offer malformed = offerAt(2 * kSecond);
  malformed.malformed = "position has 40 entries (at most 16)";
  gate_.offer(malformed, true, submit);
  gate_.offer(offerAt(3 * kSecond), false, submit);
  // Refused with the reason the transport named: a chunk longer than a chunk may be.
  Offer long_chunk = offerAt(4 * kSecond);
  long_chunk.malformed = "a chunk carries 1 to 64 waypoints, this one 65";
  long_chunk.malformed_reason = commandReason(RejectionReason::kInvalidChunk);
  EXPECT_EQ(gate_.offer(long_chunk, true, submit), commandReason(RejectionReason::kInvalidChunk));
  EXPECT_EQ(asked, 0);
  const std::vector<CommandOutcome> outcomes = gate_.takeOutcomes();
  ASSERT_EQ(outcomes.size(), 4U);
  EXPECT_EQ(outcomes[0].reason, CommandReason::kWrongKind);
  EXPECT_EQ(outcomes[0].kind, CommandKind::kJoint);
  EXPECT_EQ(outcomes[1].reason, commandReason(RejectionReason::kDofMismatch));
  EXPECT_EQ(outcomes[1].message, "position has 40 entries (at most 16)");
  EXPECT_EQ(outcomes[2].reason, CommandReason::kInactive);
  EXPECT_EQ(toString(outcomes[2].reason), "inactive");
  EXPECT_EQ(toString(outcomes[3].reason), "invalid_chunk");
  EXPECT_EQ(outcomes[3].message, long_chunk.malformed);
}

TEST_F(CommandGateTest, EveryCommandIsAccountedExactlyOnce) {
  for (int i = 1; i <= 50; ++i) {
    // Every third one refused by the wrapper, the rest accepted.
    gate_.offer(offerAt((i + 10) * kSecond), true, [&](std::int64_t) {
      return i % 3 == 0 ? Verdict{false, RejectionReason::kStaleStamp, "stale_stamp: older"}
                        : accepted();
    });
  }
  // The cycle took the first 20 accepted ones; the rest never reach a cycle.
  ASSERT_TRUE(noteCycle(7, 20, 1));
  gate_.settle();
  gate_.abandonPending("the host shut down before a cycle took it");
  const GateCounts counts = gate_.counts();
  const std::vector<CommandOutcome> outcomes = gate_.takeOutcomes();
  EXPECT_EQ(counts.received, 50U);
  EXPECT_EQ(outcomes.size(), 50U);
  EXPECT_EQ(counts.applied, 20U);
  EXPECT_EQ(counts.applied + counts.rejected, 50U);
  std::uint64_t applied = 0;
  for (const CommandOutcome& outcome : outcomes) {
    applied += outcome.applied ? 1 : 0;
    if (outcome.applied) {
      EXPECT_LE(outcome.sequence, 20U);
      EXPECT_EQ(outcome.cycle, 7U);
    }
  }
  EXPECT_EQ(applied, counts.applied);
  EXPECT_EQ(
      counts.per_reason[static_cast<std::size_t>(CommandReason::kInactive)],
      counts.rejected -
          counts.per_reason[static_cast<std::size_t>(commandReason(RejectionReason::kStaleStamp))]);
}

// A sender whose clock runs an hour ahead used to be applied, after which every other sender's
// stamps were stale until the host restarted.
TEST_F(CommandGateTest, AStampTooFarAheadOfTheHostClockIsRefusedAndLocksNoOneOut) {
  const std::int64_t host_now = 1000 * kSecond;
  Offer ahead = offerAt(host_now + 3600 * kSecond);
  ahead.clock_ns = host_now;
  std::vector<CommandOutcome> outcomes = offer(ahead);
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_EQ(outcomes[0].reason, CommandReason::kFutureStamp);
  EXPECT_EQ(toString(outcomes[0].reason), "future_stamp");
  EXPECT_NE(outcomes[0].message.find("3600 s ahead of the host's clock"), std::string::npos)
      << outcomes[0].message;
  // Within the lead (1 s by default) a clock that runs a little ahead is fine.
  Offer slightly_ahead = offerAt(host_now + kSecond / 2);
  slightly_ahead.clock_ns = host_now;
  EXPECT_TRUE(offer(slightly_ahead).empty());
}

TEST_F(CommandGateTest, NanosecondsOutOfRangeAreAnInvalidStamp) {
  Offer invalid = offerAt(5 * kSecond);
  invalid.nanosec = 4'000'000'000U;  // sec 1 + 4e9 ns would read as 5 s
  std::vector<CommandOutcome> outcomes = offer(invalid);
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_EQ(outcomes[0].reason, CommandReason::kInvalidStamp);
  EXPECT_EQ(outcomes[0].nanosec, 4'000'000'000U) << "the stamp as sent, for its outcome";
  EXPECT_NE(outcomes[0].message.find("header.stamp.nanosec 4000000000 is out of range"),
            std::string::npos)
      << outcomes[0].message;
  Offer valid = offerAt(5 * kSecond);
  valid.nanosec = 999'999'999U;
  EXPECT_TRUE(offer(valid).empty());
}

TEST(CommandGateOptions, TheStampLeadComesFromTheControllerFile) {
  WrapperConfig config =
      fr3Config(kCartesianImpedancePlugin, "validation:\n  max_stamp_lead_s: 0.25\n");
  const GateOptions options = gateOptions(config, true);
  EXPECT_EQ(options.max_stamp_lead_s, 0.25);
  EXPECT_EQ(options.kind, CommandKind::kCartesian);
  EXPECT_EQ(options.publisher_timeout_s, config.command_timeout_s);
  EXPECT_EQ(gateOptions(fr3Config(kJointImpedancePlugin), false).max_stamp_lead_s, 1.0);
}

/// The gate with a joint wrapper behind it, as the hosts have it: the stamp rule (the wrapper's
/// one stamp floor, in integer nanoseconds) and the numbers that settle outcomes.
class CommandGateWithWrapper : public ::testing::Test {
 protected:
  CommandGateWithWrapper() { wrapper_.activate(state_); }

  /// A stiffness command stamped `stamp_ns` on the wire (`stiffness` NaN: the wrapper refuses it).
  std::vector<CommandOutcome> offer(std::int64_t stamp_ns, double stiffness = 100.0) {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.fields = CommandField::kStiffness;
    command.stiffness.setConstant(stiffness);
    command.stamp_s = stampSeconds(stamp_ns);
    Offer offer;
    offer.stamp_ns = stamp_ns;
    offer.kind = CommandKind::kJoint;
    offer.publisher = kWriterA;
    gate_.offer(offer, true, [&](std::int64_t wire_stamp_ns) {
      return wrapper_.submit(command, wire_stamp_ns);
    });
    return gate_.takeOutcomes();
  }
  /// One control cycle, reported to the gate as the hosts report it; the outcomes it settled.
  std::vector<CommandOutcome> cycle(std::uint64_t index) {
    std::vector<double> torque(kFr3Dof, 0.0);
    EXPECT_NE(wrapper_.update(state_, kPeriod, torque), CycleStatus::kInactive);
    EXPECT_TRUE(
        gate_.noteCycle(index, wrapper_.controller().idInForce(), [] { return std::int64_t{99}; }));
    gate_.settle();
    return gate_.takeOutcomes();
  }

  JointWrapper wrapper_{fr3Config(kJointImpedancePlugin)};
  JointState state_ = restingAt(wrapper_.controller(), fr3Home());
  CommandGate gate_{{.kind = CommandKind::kJoint, .publisher_timeout_s = 0.5}};
};

TEST_F(CommandGateWithWrapper, StampsMustIncreaseStrictlyToTheNanosecond) {
  const std::int64_t stamp = 1'764'000'000 * kSecond + 123'456'789;
  EXPECT_TRUE(offer(stamp).empty());
  // Equal: refused. One nanosecond newer: accepted, though both are the same double in seconds.
  std::vector<CommandOutcome> equal = offer(stamp);
  ASSERT_EQ(equal.size(), 1U);
  EXPECT_FALSE(equal[0].applied);
  EXPECT_EQ(equal[0].reason, commandReason(RejectionReason::kStaleStamp));
  EXPECT_NE(equal[0].message.find("1764000000.123456789 s"), std::string::npos) << equal[0].message;
  EXPECT_EQ(gate_.counts().last_rejection.rfind("stale_stamp: stamp ", 0), 0U)
      << gate_.counts().last_rejection;
  EXPECT_TRUE(offer(stamp + 1).empty());
  std::vector<CommandOutcome> older = offer(stamp - kSecond);
  ASSERT_EQ(older.size(), 1U);
  EXPECT_EQ(older[0].reason, commandReason(RejectionReason::kStaleStamp));
  EXPECT_EQ(older[0].stamp_ns, stamp - kSecond);
}

// At today's epoch a double in seconds resolves about 0.24 us: two commands 0.1 us apart were the
// same stamp in force, so the second was never settled (or both as one). Numbers tell them apart.
TEST_F(CommandGateWithWrapper, TwoCommandsATenthOfAMicrosecondApartAreSettledApart) {
  const std::int64_t first = 1'764'000'000 * kSecond + 123'456'700;
  const std::int64_t second = first + 100;
  ASSERT_EQ(stampSeconds(first), stampSeconds(second)) << "the premise: one double for both";
  EXPECT_TRUE(offer(first).empty());
  std::vector<CommandOutcome> settled = cycle(1);
  ASSERT_EQ(settled.size(), 1U);
  EXPECT_EQ(settled[0].stamp_ns, first);
  EXPECT_EQ(settled[0].cycle, 1U);
  EXPECT_EQ(wrapper_.controller().idInForce().stamp_ns, first);

  EXPECT_TRUE(offer(second).empty());
  settled = cycle(2);
  ASSERT_EQ(settled.size(), 1U) << "the second command is settled by the cycle that took it";
  EXPECT_TRUE(settled[0].applied);
  EXPECT_EQ(settled[0].stamp_ns, second);
  EXPECT_EQ(settled[0].cycle, 2U);
  EXPECT_EQ(settled[0].sequence, 2U);
  EXPECT_EQ(wrapper_.controller().idInForce().stamp_ns, second) << "exact, as the state reports";
  EXPECT_EQ(gate_.counts().applied, 2U);
  EXPECT_EQ(gate_.pending(), 0U);
}

TEST_F(CommandGateWithWrapper, AStampBeforeTheEpochIsNamedExactly) {
  // The wire's seconds are signed: a stamp before the epoch (a sender's clock gone wrong) must be
  // refused with a readable reason, nanoseconds in [0, 1e9) as builtin_interfaces/Time has them.
  EXPECT_TRUE(offer(5 * kSecond).empty());
  const std::vector<CommandOutcome> before = offer(-1);
  ASSERT_EQ(before.size(), 1U);
  EXPECT_EQ(before[0].reason, commandReason(RejectionReason::kStaleStamp));
  EXPECT_NE(before[0].message.find("stamp -1.999999999 s is not newer"), std::string::npos)
      << before[0].message;
  const std::int64_t earliest_on_the_wire = -2'147'483'648LL * kSecond;  // int32 seconds
  const std::vector<CommandOutcome> earliest = offer(earliest_on_the_wire);
  ASSERT_EQ(earliest.size(), 1U);
  EXPECT_NE(earliest[0].message.find("stamp -2147483648.000000000 s"), std::string::npos)
      << earliest[0].message;
}

TEST_F(CommandGateWithWrapper, ARefusedCommandDoesNotMoveTheStampFloor) {
  EXPECT_TRUE(offer(5 * kSecond).empty());
  std::vector<CommandOutcome> refused = offer(7 * kSecond, std::nan(""));
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0].reason, commandReason(RejectionReason::kNonFinite));
  // 6 s is newer than the last *accepted* command (5 s), so it passes.
  EXPECT_TRUE(offer(6 * kSecond).empty());
}

TEST_F(CommandGateWithWrapper, AResetClearsTheOneStampFloor) {
  EXPECT_TRUE(offer(50 * kSecond).empty());
  std::vector<CommandOutcome> outcomes = offer(10 * kSecond);
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_EQ(outcomes[0].reason, commandReason(RejectionReason::kStaleStamp));
  wrapper_.reset();
  EXPECT_TRUE(offer(10 * kSecond).empty()) << "after a reset any stamp is new again";
}

// A direct caller's stamp_s (a task file, an experiment) may repeat the last one, never go back;
// one beyond what integer nanoseconds hold stands at the end of the range, without overflow.
TEST_F(CommandGateWithWrapper, ADirectCallersStampMayRepeatAndIsJudgedInTheSameFloor) {
  JointCommand command = JointCommand::zero(kFr3Dof);
  command.fields = CommandField::kStiffness;
  command.stiffness.setConstant(100.0);
  command.stamp_s = 2.5;
  EXPECT_TRUE(wrapper_.submit(command).accepted);
  EXPECT_TRUE(wrapper_.submit(command).accepted) << "the same stamp again";
  command.stamp_s = 2.4;
  EXPECT_EQ(wrapper_.submit(command).reason, RejectionReason::kStaleStamp);
  EXPECT_EQ(wrapper_.diagnostics().rejectionsTotal(), 1U) << "counted once, by the wrapper";
  // A wire command must be newer than the direct one: one floor for both.
  EXPECT_EQ(offer(stampNanoseconds(2.5)).size(), 1U);
  EXPECT_TRUE(offer(stampNanoseconds(2.5) + 1).empty());
  command.stamp_s = 1e300;
  EXPECT_TRUE(wrapper_.submit(command).accepted);
  command.stamp_s = 5.0;
  EXPECT_EQ(wrapper_.submit(command).reason, RejectionReason::kStaleStamp);
}

TEST_F(CommandGateWithWrapper, TheGateCountsWhatItOffersAndTheWrapperDoesNotCountItAgain) {
  EXPECT_TRUE(offer(5 * kSecond).empty());
  EXPECT_EQ(offer(4 * kSecond).size(), 1U);
  EXPECT_EQ(offer(6 * kSecond, std::nan("")).size(), 1U);
  EXPECT_EQ(gate_.counts().rejected, 2U);
  EXPECT_EQ(wrapper_.diagnostics().rejectionsTotal(), 0U) << "one count per command";
}

TEST(CommandGateWithWrapperQueue, AFullQueueIsRefusedAsQueueFullAndTheRestApplyInOrder) {
  JointWrapper wrapper(fr3Config(kJointImpedancePlugin));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  CommandGate gate({.kind = CommandKind::kJoint, .publisher_timeout_s = 0.5});
  // More commands than the wrapper queues between two cycles: the surplus is queue_full.
  int offered = 0;
  for (int i = 1; i <= 100; ++i) {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.stamp_s = stampSeconds(static_cast<std::int64_t>(i) * 1'000'000);
    command.fields = CommandField::kPosition;
    command.position = fr3Home();
    Offer offer;
    offer.stamp_ns = static_cast<std::int64_t>(i) * 1'000'000;
    offer.kind = CommandKind::kJoint;
    offer.publisher = kWriterA;
    gate.offer(offer, true,
               [&](std::int64_t stamp_ns) { return wrapper.submit(command, stamp_ns); });
    ++offered;
  }
  std::vector<double> torque(kFr3Dof, 0.0);
  ASSERT_NE(wrapper.update(state, kPeriod, torque), CycleStatus::kInactive);
  ASSERT_TRUE(gate.noteCycle(0, wrapper.controller().idInForce(), [] { return std::int64_t{99}; }));
  gate.settle();
  const GateCounts counts = gate.counts();
  const std::size_t queue_full =
      counts.per_reason[static_cast<std::size_t>(commandReason(RejectionReason::kQueueFull))];
  EXPECT_GT(queue_full, 0U);
  EXPECT_GT(counts.applied, 0U);
  EXPECT_EQ(counts.applied + queue_full, static_cast<std::uint64_t>(offered));
  EXPECT_EQ(gate.pending(), 0U);
  std::int64_t previous = 0;
  for (const CommandOutcome& outcome : gate.takeOutcomes()) {
    if (outcome.applied) {
      EXPECT_GT(outcome.stamp_ns, previous);
      EXPECT_EQ(outcome.cycle, 0U);
      previous = outcome.stamp_ns;
    }
  }
}

}  // namespace
}  // namespace comply::pipeline
