// Timed chunks through the wrapper on the FR3: validated as a whole at the intake (a late or
// malformed chunk is refused with its reason and changes nothing), played by the cycle at the
// host's times, gains reaching the law at their waypoints, commands and the watchdog around it.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <thread>

#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/schema/schema.hpp"
#include "resting_fr3.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kHostStart = 1000.0;  // s: the host's clock at activation (any timebase)
constexpr std::int64_t kSecondNs = 1'000'000'000;

class CartesianChunks : public RestingFr3 {
 protected:
  // A 20 ms blend, short for the tests' timing: blending a chunk's lead-in in over it asks 14 to
  // 50 m/s^2 of the reference, and the takeover and skipped-waypoint tests step it 2 to 3 cm in
  // it (1 to 2 m/s), above the intake's 13 m/s^2 and 1 m/s. Those limits are off here; they have
  // their own tests (chunk_limits_test.cpp).
  CartesianChunks()
      : RestingFr3(
            "command_timeout_s: 0.05\nchunk_blend_time_s: 0.02\nfrozen_state_timeout_s: 0\n"
            "validation:\n  max_chunk_acceleration_m_per_s2: 0\n"
            "governor:\n  tcp_speed_m_per_s: 0\n"
            "torque_rate_limit_nm_per_s: " +
                std::to_string(kNoRateLimit) + "\n",
            kHostStart) {}

  /// `count` waypoints from now + `first_s`, `spacing_s` apart, moving 1 cm along x per waypoint
  /// with the stiffness along x rising 500 N/m per waypoint.
  CartesianChunk chunk(int count, double first_s = 0.02, double spacing_s = 0.05) {
    CartesianChunk c;
    c.stamp_s = ++stamp;
    c.fields = CommandField::kPosition | CommandField::kStiffness;
    for (int k = 0; k < count; ++k) {
      ChunkWaypoint<CartesianCommand> waypoint{hostTime() + first_s + spacing_s * k,
                                               CartesianCommand::zero(kFr3Dof)};
      waypoint.command.position = home_position + Eigen::Vector3d(0.01 * k, 0.0, 0.0);
      waypoint.command.orientation = home_orientation;
      waypoint.command.stiffness_translational =
          Eigen::Vector3d(1000.0 + 500.0 * k, 800.0, 800.0).asDiagonal();
      waypoint.command.stiffness_rotational = 40.0 * Eigen::Matrix3d::Identity();
      c.waypoints.push_back(waypoint);
    }
    return c;
  }

  double stamp = 0.0;
};

TEST_F(CartesianChunks, PlaysThroughItsWaypointsAtTheirTimesWithTheGainsOfEach) {
  const CartesianChunk c = chunk(5);
  ASSERT_TRUE(wrapper.submitChunk(c, hostTime()).accepted);
  for (std::size_t k = 1; k < c.waypoints.size(); ++k) {
    // The cycle at a waypoint's time (the controller runs a chunk up to one period early).
    while (hostTime() + kPeriod < c.waypoints[k].time_s - 1e-9) {
      cycles(1);
    }
    cycles(1);
    SCOPED_TRACE(k);
    EXPECT_LT((reference() - c.waypoints[k].command.position).norm(), 2e-4);
    EXPECT_NEAR(law().stiffness_translational[0], 1000.0 + 500.0 * static_cast<double>(k), 25.0);
  }
  cycles(5);
  EXPECT_LT((reference() - c.waypoints.back().command.position).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(law().stiffness_translational[0], 3000.0);
  EXPECT_EQ(Eigen::Map<const Vector6d>(law().twist).norm(), 0.0) << "held at rest after the end";
  EXPECT_EQ(wrapper.controller().idInForce().stamp_ns, stampNanoseconds(c.stamp_s));
}

TEST_F(CartesianChunks, ALateOrMalformedChunkIsRefusedWithItsReasonAndChangesNothing) {
  const Eigen::Vector3d before = reference();
  const double stiffness_before = law().stiffness_translational[0];
  struct Case {
    const char* what;
    RejectionReason reason;
    const char* names;
    std::function<void(CartesianChunk&)> spoil;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {"late", RejectionReason::kLateChunk, "last waypoint was due",
       [this](CartesianChunk& c) {
         for (auto& w : c.waypoints) {
           w.time_s -= 1.0;
         }
       }},
      {"empty", RejectionReason::kInvalidChunk, "1 to 64 waypoints",
       [](CartesianChunk& c) { c.waypoints.clear(); }},
      {"too many", RejectionReason::kInvalidChunk, "this one 65",
       [](CartesianChunk& c) { c.waypoints.resize(65, c.waypoints.back()); }},
      {"times not increasing", RejectionReason::kInvalidChunk, "waypoint 2's time",
       [](CartesianChunk& c) { c.waypoints[2].time_s = c.waypoints[1].time_s; }},
      {"no position", RejectionReason::kInvalidChunk, "must set the position",
       [](CartesianChunk& c) { c.fields = CommandField::kStiffness; }},
      {"acceleration", RejectionReason::kInvalidChunk, "cannot set acceleration",
       [](CartesianChunk& c) { c.fields = c.fields | CommandField::kAcceleration; }},
      {"NaN in a waypoint", RejectionReason::kNonFinite, "waypoint 3: non_finite",
       [nan](CartesianChunk& c) { c.waypoints[3].command.position.y() = nan; }},
      {"NaN time", RejectionReason::kNonFinite, "waypoint 1 time is not finite",
       [nan](CartesianChunk& c) { c.waypoints[1].time_s = nan; }},
      {"gains not PSD", RejectionReason::kInvalidGains, "waypoint 4",
       [](CartesianChunk& c) { c.waypoints[4].command.stiffness_translational(1, 1) = -5.0; }},
      {"first waypoint far away", RejectionReason::kPoseJump, "waypoint 0",
       [](CartesianChunk& c) {
         for (auto& w : c.waypoints) {
           w.command.position.z() += 0.3;
         }
       }},
      {"a jump between waypoints", RejectionReason::kPoseJump, "waypoint 2",
       [](CartesianChunk& c) {
         for (std::size_t k = 2; k < c.waypoints.size(); ++k) {
           c.waypoints[k].command.position.z() += 0.3;
         }
       }},
      {"stale stamp", RejectionReason::kStaleStamp, "stale_stamp: stamp is older",
       [](CartesianChunk& c) { c.stamp_s = -1.0; }},
  };
  for (const Case& test : cases) {
    SCOPED_TRACE(test.what);
    CartesianChunk c = chunk(5);
    test.spoil(c);
    const Verdict verdict = wrapper.submitChunk(c, hostTime());
    EXPECT_FALSE(verdict.accepted);
    EXPECT_EQ(verdict.reason, test.reason) << verdict.message;
    EXPECT_NE(verdict.message.find(test.names), std::string::npos) << verdict.message;
    cycles(3);
    EXPECT_LT((reference() - before).norm(), 1e-12);
    EXPECT_EQ(law().stiffness_translational[0], stiffness_before);
  }
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.rejections[static_cast<std::size_t>(RejectionReason::kLateChunk)], 1U);
  EXPECT_EQ(diagnostics.rejections[static_cast<std::size_t>(RejectionReason::kInvalidChunk)], 5U);
}

TEST_F(CartesianChunks, ChunksFasterThanTheCycleRunOutOfSlotsAndTheNextCycleFreesThem) {
  for (int k = 0; k < ChunkPlayer::kSlots; ++k) {
    ASSERT_TRUE(wrapper.submitChunk(chunk(3), hostTime()).accepted) << k;
  }
  const Verdict full = wrapper.submitChunk(chunk(3), hostTime());
  EXPECT_EQ(full.reason, RejectionReason::kQueueFull);
  EXPECT_NE(full.message.find("chunk slots are taken"), std::string::npos) << full.message;
  cycles(1);  // starts the last, frees the others
  EXPECT_TRUE(wrapper.submitChunk(chunk(3), hostTime()).accepted);
}

// The intake on its own thread loading chunks and commands as fast as it can while the cycle
// plays them: the slots pass between the two threads without a lock (under ThreadSanitizer in
// make test-tsan), every chunk is accepted or refused for want of a slot, and the cycle never
// leaves normal operation.
TEST_F(CartesianChunks, ASenderOnAnotherThreadAndTheCycleShareTheSlotsSafely) {
  constexpr int kChunks = 500;
  std::atomic<bool> sent{false};
  std::atomic<int> accepted{0};
  std::atomic<int> full{0};
  std::atomic<double> host_time_s{hostTime()};
  const Eigen::Vector3d home = home_position;
  const Eigen::Quaterniond orientation = home_orientation;
  std::thread sender([&] {
    for (int k = 0; k < kChunks; ++k) {
      CartesianChunk c;
      c.stamp_s = 1.0 + k;
      c.fields = CommandField::kPosition | CommandField::kStiffness;
      const double now_s = host_time_s.load();
      for (int j = 0; j < 8; ++j) {
        ChunkWaypoint<CartesianCommand> waypoint{now_s + 0.01 * (j + 1),
                                                 CartesianCommand::zero(kFr3Dof)};
        waypoint.command.position = home + Eigen::Vector3d(0.001 * (k % 5), 0.0005 * j, 0.0);
        waypoint.command.orientation = orientation;
        waypoint.command.stiffness_translational = (500.0 + j) * Eigen::Matrix3d::Identity();
        waypoint.command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
        c.waypoints.push_back(waypoint);
      }
      const Verdict verdict = wrapper.submitChunk(c, now_s);
      (verdict.accepted ? accepted : full) += 1;
      if (!verdict.accepted && verdict.reason != RejectionReason::kQueueFull) {
        ADD_FAILURE() << verdict.message;
      }
    }
    sent.store(true);
  });
  // The cycle runs until the sender is done (as fast as it can: the sender's chunks meet slots
  // that are loaded, waiting, playing and freed).
  while (!sent.load()) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    ++cycle_count;
    host_time_s.store(hostTime());
  }
  sender.join();
  EXPECT_EQ(accepted.load() + full.load(), kChunks);
  EXPECT_GT(accepted.load(), 0);
  EXPECT_EQ(wrapper.diagnostics().faults, 0U);
}

TEST_F(CartesianChunks, AWaypointAlreadyPastIsSkippedAndNotComparedWithTheArm) {
  // The policy acted on an old observation: its first waypoints are behind the host's clock and
  // 3 cm away, where the arm no longer is; the first one still ahead is checked and played.
  CartesianChunk c = chunk(6, -0.12, 0.05);
  const Verdict verdict = wrapper.submitChunk(c, hostTime());
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  cycles(200);
  EXPECT_LT((reference() - c.waypoints.back().command.position).norm(), 1e-12);
}

TEST_F(CartesianChunks, ACommandOnTheChunksGroupsEndsItAndOneOnOtherGroupsDoesNot) {
  ASSERT_TRUE(wrapper.submitChunk(chunk(5), hostTime()).accepted);
  cycles(60);
  // Damping is not the chunk's: merged, the chunk plays on.
  CartesianCommand damping = CartesianCommand::zero(kFr3Dof);
  damping.stamp_s = ++stamp;
  damping.fields = CommandField::kDamping;
  damping.damping_mode = DampingMode::kAbsolute;
  damping.damping_translational = 77.0 * Eigen::Matrix3d::Identity();
  damping.damping_rotational = 3.0 * Eigen::Matrix3d::Identity();
  ASSERT_TRUE(wrapper.submit(damping).accepted);
  const Eigen::Vector3d at_command = reference();
  cycles(20);
  EXPECT_GT((reference() - at_command).norm(), 1e-3) << "the chunk stopped";
  EXPECT_EQ(law().damping_translational[0], 77.0);
  // A stiffness command is the chunk's: the reference stays where the chunk had it, at rest.
  CartesianCommand stiffness = CartesianCommand::zero(kFr3Dof);
  stiffness.stamp_s = ++stamp;
  stiffness.fields = CommandField::kStiffness;
  stiffness.stiffness_translational = 600.0 * Eigen::Matrix3d::Identity();
  stiffness.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
  ASSERT_TRUE(wrapper.submit(stiffness).accepted);
  cycles(1);
  const Eigen::Vector3d stopped = reference();
  cycles(50);
  EXPECT_LT((reference() - stopped).norm(), 1e-12);
  EXPECT_EQ(Eigen::Map<const Vector6d>(law().twist).norm(), 0.0);
  EXPECT_EQ(law().stiffness_translational[0], 600.0);
}

TEST_F(CartesianChunks, AChunkTakenInFaultIsInForceButDoesNotMove) {
  JointState bad = state;
  bad.position[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(wrapper.update(bad, kPeriod, torque.span()), CycleStatus::kFault);
  ++cycle_count;
  const Eigen::Vector3d held = reference();
  const CartesianChunk c = chunk(5);
  ASSERT_TRUE(wrapper.submitChunk(c, hostTime()).accepted);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
    ++cycle_count;
  }
  // Accounted as applied (its stamp in force), but the fault stopped it where the reference was.
  EXPECT_EQ(wrapper.controller().idInForce().stamp_ns, stampNanoseconds(c.stamp_s));
  EXPECT_LT(
      (Eigen::Map<const Eigen::Vector3d>(
           std::get<comply_cartesian_command>(wrapper.controller().activeCommand()).position) -
       held)
          .norm(),
      1e-12);
}

TEST_F(CartesianChunks, TheWatchdogWaitsForTheChunksEndAndCountsFromThere) {
  // 0.22 s of chunk with a 0.05 s command timeout.
  const CartesianChunk c = chunk(5);
  ASSERT_TRUE(wrapper.submitChunk(c, hostTime()).accepted);
  cycles(200);
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 0U);
  cycles(80);
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 1U);
  EXPECT_LT((reference() - c.waypoints.back().command.position).norm(), 1e-12);
}

TEST_F(CartesianChunks, ANewChunkTakesOverWithoutAJump) {
  ASSERT_TRUE(wrapper.submitChunk(chunk(5), hostTime()).accepted);
  cycles(70);  // mid-motion
  Eigen::Vector3d last = reference();
  Eigen::Vector3d last_velocity = Eigen::Map<const Eigen::Vector3d>(law().twist);
  // The new chunk goes back the way it came, 2 cm off to the side.
  CartesianChunk back = chunk(4);
  for (std::size_t k = 0; k < back.waypoints.size(); ++k) {
    back.waypoints[k].command.position =
        last + Eigen::Vector3d(-0.01 * static_cast<double>(k), 0.02, 0.0);
  }
  const Verdict verdict = wrapper.submitChunk(back, hostTime());
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  // Across the takeover and the 20 ms blend (a 2 cm step taken in 20 ms: up to 1.9 m/s), every
  // cycle's step in position is what the reported velocities carry it (to 2 % of the largest
  // step), and no step in velocity exceeds what the reported accelerations allow: no jump in
  // either. (The acceleration itself may step at a waypoint: the curve is C1.)
  Eigen::Vector3d last_acceleration = Eigen::Map<const Eigen::Vector3d>(law().acceleration);
  double position_mismatch = 0.0;
  double velocity_mismatch = 0.0;  // largest ratio
  for (int i = 0; i < 300; ++i) {
    cycles(1);
    const Eigen::Vector3d velocity = Eigen::Map<const Eigen::Vector3d>(law().twist);
    const Eigen::Vector3d acceleration = Eigen::Map<const Eigen::Vector3d>(law().acceleration);
    position_mismatch =
        std::max(position_mismatch,
                 (reference() - last - 0.5 * kPeriod * (velocity + last_velocity)).norm());
    // The acceleration moves inside a cycle too (cubic in time along the blend): 5 % leeway.
    velocity_mismatch =
        std::max(velocity_mismatch,
                 (velocity - last_velocity).norm() /
                     (1e-9 + kPeriod * std::max(acceleration.norm(), last_acceleration.norm())));
    last = reference();
    last_velocity = velocity;
    last_acceleration = acceleration;
  }
  EXPECT_LT(position_mismatch, 4e-5) << "m";
  EXPECT_LT(velocity_mismatch, 1.05) << "velocity step / (period * acceleration)";
  EXPECT_LT((reference() - back.waypoints.back().command.position).norm(), 1e-12);
}

// A chunk waiting for its start, through the command gate as every host passes it: the red team's
// chunk 5 s ahead, its sender gone, left every other sender's commands without an outcome until its
// time. Another sender's commands are applied by the next cycle each while it waits; its sender's
// departure (CommandGate::releasePublisher, then Wrapper::dropWaitingChunk) drops it, as a reset
// does: the reference never moves to it.
TEST_F(CartesianChunks, AWaitingChunkHoldsNoOneAndGoesWithItsSenderOrAReset) {
  CommandGate gate({.kind = CommandKind::kCartesian, .publisher_timeout_s = 0.05});
  constexpr std::uint64_t kChunkSender = 0xA;
  constexpr std::uint64_t kOtherSender = 0xB;
  const auto offerOf = [](std::uint64_t publisher, std::int64_t stamp_ns, bool chunk) {
    Offer offer;
    offer.stamp_ns = stamp_ns;
    offer.publisher = publisher;
    offer.chunk = chunk;
    return offer;
  };
  const auto settled = [&] {
    gate.noteCycle(cycle_count, wrapper.controller().idInForce(), [] { return 0; });
    gate.settle();
    return gate.takeOutcomes();
  };
  const auto offerChunk = [&](std::int64_t stamp_ns) {
    CartesianChunk waiting = chunk(5, 0.8);  // within validation.max_stamp_lead_s
    return gate.offer(offerOf(kChunkSender, stamp_ns, true), true, [&](std::int64_t ns) {
      return wrapper.submitChunk(waiting, hostTime(), ns);
    });
  };
  const Eigen::Vector3d before = reference();
  ASSERT_EQ(offerChunk(kSecondNs), CommandReason::kNone);
  cycles(1);
  std::vector<CommandOutcome> outcomes = settled();
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_TRUE(outcomes[0].applied);
  const std::uint64_t chunk_sequence = outcomes[0].sequence;
  ASSERT_TRUE(wrapper.controller().chunks().playing());

  EXPECT_EQ(gate.releasePublisher(kChunkSender), chunk_sequence) << "the departed sender's chunk";
  EXPECT_EQ(gate.releasePublisher(kChunkSender), 0U) << "named once";
  for (int k = 1; k <= 3; ++k) {
    CartesianCommand probe = CartesianCommand::zero(kFr3Dof);
    probe.fields = CommandField::kNone;
    ASSERT_EQ(gate.offer(offerOf(kOtherSender, kSecondNs + k, false), true,
                         [&](std::int64_t ns) { return wrapper.submit(probe, ns); }),
              CommandReason::kNone);
    cycles(1);
    outcomes = settled();
    ASSERT_EQ(outcomes.size(), 1U) << "the other sender's command waits for the chunk";
    EXPECT_TRUE(outcomes[0].applied) << outcomes[0].message;
  }
  EXPECT_TRUE(wrapper.controller().chunks().playing()) << "a command on no group leaves it";
  wrapper.dropWaitingChunk(chunk_sequence);
  cycles(1);
  EXPECT_FALSE(wrapper.controller().chunks().playing());
  cycles(1200);  // past the chunk's last waypoint, 1 s from its start
  EXPECT_LT((reference() - before).norm(), 0.006) << "the departed sender's chunk played";
  EXPECT_EQ(Eigen::Map<const Vector6d>(law().twist).norm(), 0.0);

  // A reset drops a waiting chunk too (the stamp floor goes with it).
  const Eigen::Vector3d held = reference();
  gate.releasePublisher(kOtherSender);
  ASSERT_EQ(offerChunk(3 * kSecondNs), CommandReason::kNone);
  cycles(1);
  ASSERT_TRUE(wrapper.controller().chunks().playing());
  wrapper.reset();
  cycles(1);
  EXPECT_FALSE(wrapper.controller().chunks().playing());
  cycles(1200);
  EXPECT_LT((reference() - held).norm(), 0.006);
}

}  // namespace
}  // namespace comply::pipeline::test
