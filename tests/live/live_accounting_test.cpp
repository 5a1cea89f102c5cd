// A live host with a client streaming 10,000 commands at 1 kHz, a tenth of them invalid in seven
// different ways: every command shows up exactly once, applied or rejected with the right reason.
// On DDS (`comply run`) and in process alike (live_harness.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <thread>

#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

using transport::Reason;

constexpr int kCommands = 10000;

/// The i-th command of the stream and the reason it must be refused for (kNone: applied).
struct Planned {
  bool joint = false;
  transport::CartesianCommandMessage cartesian;
  transport::JointCommandMessage joint_message;
  Reason reason = Reason::kNone;
};

Planned plan(int i, const transport::ControllerStateMessage& state, std::int64_t base_ns) {
  const auto stampAt = [&](double ms) {
    return transport::Stamp::fromNanoseconds(base_ns + static_cast<std::int64_t>(ms * 1e6));
  };
  const double angle = 2.0 * M_PI * i / 2000.0;  // a 1 cm circle every 2 s
  Planned p;
  p.cartesian =
      poseCommand(state, {0.0, 0.01 * std::sin(angle), 0.01 * (std::cos(angle) - 1.0)}, stampAt(i));
  CartesianCommand& c = p.cartesian.command;
  if (i % 10 != 9) {
    return p;
  }
  switch ((i / 10) % 7) {
    case 0:
      c.position.x() = std::nan("");
      p.reason = Reason::kNonFinite;
      break;
    case 1:
      c.orientation.coeffs() *= 1.1;
      p.reason = Reason::kInvalidQuaternion;
      break;
    case 2:
      c.fields = CommandField::kStiffness;
      c.stiffness_translational = -Eigen::Matrix3d::Identity();
      c.stiffness_rotational = Eigen::Matrix3d::Identity();
      p.reason = Reason::kInvalidGains;
      break;
    case 3:
      c.fields = CommandField::kNullspace;
      c.nullspace_position.setZero(3);
      c.nullspace_stiffness.setZero(3);
      c.nullspace_damping.setZero(3);
      p.reason = Reason::kDofMismatch;
      break;
    case 4:
      p.cartesian.header.stamp = stampAt(i - 5.5);  // older than the commands before it
      p.reason = Reason::kStaleStamp;
      break;
    case 5:
      c.position.x() += 0.5;
      p.reason = Reason::kPoseJump;
      break;
    default:
      p.joint = true;
      p.joint_message.header.stamp = p.cartesian.header.stamp;
      p.joint_message.command = JointCommand::zero(static_cast<int>(state.position.size()));
      p.reason = Reason::kWrongKind;
      break;
  }
  return p;
}

TEST_P(LiveHostOn, MixedStreamIsAccountedExactlyOnce) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("mixed", 1);
  ASSERT_TRUE(state);
  host.poll(300ms, [](const auto&) { return false; });  // the probes' last outcomes
  host.outcomes().clear();
  const transport::DiagnosticsMessage before = host.last();

  std::map<std::int64_t, Reason> expected;
  const std::int64_t base_ns = transport::Stamp::now().nanoseconds();
  const auto start = Clock::now();
  for (int i = 0; i < kCommands; ++i) {
    const Planned p = plan(i, *state, base_ns);
    std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * i));
    if (p.joint) {
      ASSERT_TRUE(host.send(p.joint_message, 1));
    } else {
      ASSERT_TRUE(host.send(p.cartesian, 1));
    }
    expected[(p.joint ? p.joint_message.header.stamp : p.cartesian.header.stamp).nanoseconds()] =
        p.reason;
  }
  host.poll(20s, [&](const auto&) { return host.outcomes().size() >= expected.size(); });

  const transport::DiagnosticsMessage& last = host.last();
  std::cerr << "outcomes " << host.outcomes().size() << " of " << expected.size()
            << "; host received " << last.commands_received << ", applied " << last.commands_applied
            << ", rejected " << last.commands_rejected << "\n";
  std::map<Reason, int> refused;
  int applied = 0;
  std::uint64_t last_cycle = 0;
  for (const auto& [stamp, reason] : expected) {
    const auto found = host.outcomes().find(stamp);
    ASSERT_NE(found, host.outcomes().end()) << "command " << stamp << " has no outcome";
    ASSERT_EQ(found->second.size(), 1U) << "command " << stamp << " accounted twice";
    const transport::CommandOutcomeMessage& outcome = found->second.front();
    if (reason == Reason::kNone) {
      EXPECT_EQ(outcome.outcome, transport::Outcome::kApplied) << outcome.message;
      EXPECT_GE(outcome.cycle, last_cycle) << "applied out of order";
      last_cycle = outcome.cycle;
      ++applied;
    } else {
      EXPECT_EQ(outcome.outcome, transport::Outcome::kRejected);
      EXPECT_EQ(outcome.reason, reason) << outcome.message;
      ++refused[outcome.reason];
    }
  }
  EXPECT_EQ(host.outcomes().size(), expected.size()) << "outcomes of commands never sent";
  EXPECT_EQ(applied, kCommands * 9 / 10);
  EXPECT_EQ(refused.size(), 7U);
  EXPECT_EQ(last.commands_received - before.commands_received,
            static_cast<std::uint64_t>(kCommands));
  EXPECT_EQ(last.commands_applied - before.commands_applied, static_cast<std::uint64_t>(applied));
  const auto pose_jump = static_cast<std::size_t>(Reason::kPoseJump);
  EXPECT_EQ(last.rejections.at(pose_jump) - before.rejections.at(pose_jump),
            static_cast<std::uint64_t>(refused[Reason::kPoseJump]));
  EXPECT_EQ(last.faults, 0U);
}

/// What the gate refuses before the wrapper sees a command, from a client's side: a joint command
/// to the Cartesian controller (wrong_kind) and a command stamped like the one in force
/// (stale_stamp: stamps must be strictly newer). In process only: it is the gate's rule, not the
/// transport's, and needs no discovery.
TEST_F(LiveHostInProcess, WrongKindAndEqualStampAreRejected) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("kinds", 1);
  ASSERT_TRUE(state);
  const int dof = static_cast<int>(state->position.size());
  const auto outcomesOf = [&](transport::Stamp stamp) -> auto& {
    return host.outcomes()[stamp.nanoseconds()];
  };

  const transport::Stamp stamp = transport::Stamp::now();
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), stamp), 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return !outcomesOf(stamp).empty(); }));
  ASSERT_EQ(outcomesOf(stamp).front().outcome, transport::Outcome::kApplied)
      << outcomesOf(stamp).front().message;
  // The state names the command in force by its exact stamp, nanoseconds included (a double in
  // seconds holds only about a quarter of a microsecond at today's epoch).
  std::optional<transport::ControllerStateMessage> in_force;
  for (int attempt = 0; attempt < 100 && !(in_force && in_force->reference_stamp == stamp);
       ++attempt) {
    in_force = host.state(100ms);
  }
  ASSERT_TRUE(in_force);
  EXPECT_EQ(in_force->reference_stamp.nanoseconds(), stamp.nanoseconds());

  transport::JointCommandMessage joint;
  joint.header.stamp = transport::Stamp::fromNanoseconds(stamp.nanoseconds() + 1000000);  // +1 ms
  joint.command = JointCommand::zero(dof);
  ASSERT_TRUE(host.send(joint, 1));
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), stamp), 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) {
    return !outcomesOf(joint.header.stamp).empty() && outcomesOf(stamp).size() >= 2;
  }));

  ASSERT_EQ(outcomesOf(joint.header.stamp).size(), 1U);
  const transport::CommandOutcomeMessage& wrong_kind = outcomesOf(joint.header.stamp).front();
  EXPECT_EQ(wrong_kind.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(wrong_kind.reason, Reason::kWrongKind) << wrong_kind.message;
  EXPECT_EQ(toString(wrong_kind.reason), "wrong_kind");
  EXPECT_EQ(wrong_kind.command_kind, transport::WireCommandKind::kJoint);

  ASSERT_EQ(outcomesOf(stamp).size(), 2U) << "the equal stamp accounted other than once";
  const transport::CommandOutcomeMessage& stale = outcomesOf(stamp).back();
  EXPECT_EQ(stale.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(stale.reason, Reason::kStaleStamp) << stale.message;
  EXPECT_EQ(toString(stale.reason), "stale_stamp");
}

/// A sender whose clock is an hour ahead, and a stamp whose nanoseconds are out of range: both
/// were applied before, and the first then locked every later sender out as stale until the host
/// restarted. Now both are refused by the host's clock policy and the next command applies.
TEST_F(LiveHostInProcess, AStampFromTheFutureOrOutOfRangeIsRefusedAndLocksNoOneOut) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("clock", 1);
  ASSERT_TRUE(state);
  const auto outcomesOf = [&](transport::Stamp stamp) -> auto& {
    return host.outcomes()[stamp.nanoseconds()];
  };

  const transport::Stamp now = transport::Stamp::now();
  const transport::Stamp hour_ahead{now.sec + 3600, now.nanosec};
  transport::Stamp out_of_range{now.sec - 4, 4'000'000'000U};  // reads as "now", if summed
  const transport::Stamp next = transport::Stamp::fromNanoseconds(now.nanoseconds() + 1000000);
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), hour_ahead), 1));
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), out_of_range), 1));
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), next), 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) {
    return !outcomesOf(hour_ahead).empty() && !outcomesOf(out_of_range).empty() &&
           !outcomesOf(next).empty();
  }));
  const transport::CommandOutcomeMessage& future = outcomesOf(hour_ahead).front();
  EXPECT_EQ(future.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(toString(future.reason), "future_stamp") << future.message;
  const transport::CommandOutcomeMessage& invalid = outcomesOf(out_of_range).front();
  EXPECT_EQ(toString(invalid.reason), "invalid_stamp") << invalid.message;
  // Answered under the stamp as sent, not its sum's normal form, which its sender never sent.
  EXPECT_EQ(invalid.stamp.sec, out_of_range.sec);
  EXPECT_EQ(invalid.stamp.nanosec, out_of_range.nanosec);
  EXPECT_NE(invalid.message.find("nanosec 4000000000 is out of range"), std::string::npos)
      << invalid.message;
  const transport::CommandOutcomeMessage& applied = outcomesOf(next).front();
  EXPECT_EQ(applied.outcome, transport::Outcome::kApplied) << applied.message;
}

/// Deactivating used to leave the last torque on the simulated motors (the arm fell from a
/// 0.59 m TCP height to 0.03 m) while the state still showed the pose of the last active cycle.
/// Now the plant holds like a driver's brake, and the state shows the inactive arm where it is.
TEST_F(LiveHostInProcess, DeactivateHoldsTheArmAndTheStateSaysInactive) {
  HostHarness& host = *host_;
  host.start("deactivate");
  const auto before = host.state(20s);
  ASSERT_TRUE(before) << "no state from the host";
  ASSERT_EQ(before->state, transport::HostState::kActive);
  ASSERT_TRUE(host.request(transport::RequestType::kDeactivate, 1));
  std::optional<transport::ControllerStateMessage> after;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < deadline) {
    after = host.state(100ms);
    if (after && after->state == transport::HostState::kInactive &&
        after->cycle > before->cycle + 1000) {
      break;  // inactive for a second of control
    }
    std::this_thread::sleep_for(50ms);
  }
  ASSERT_TRUE(after);
  EXPECT_EQ(after->state, transport::HostState::kInactive);
  EXPECT_GT(after->cycle, before->cycle + 1000);
  EXPECT_NEAR(after->tcp_position[2], before->tcp_position[2], 1e-3) << "the arm fell";
  for (std::size_t i = 0; i < after->velocity.size(); ++i) {
    EXPECT_EQ(after->velocity[i], 0.0) << "joint " << i << " moves while braked";
  }
}

/// Any process could deactivate the controller: requests skipped the one-publisher rule. Now a
/// request from another process than the one holding the command topics is refused (and named in
/// the diagnostics) while the holder is heard; the holder's own process may send them.
TEST_F(LiveHostInProcess, RequestsObeyThePublisherRule) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("requests", 1);  // publisher 1 holds the topics
  ASSERT_TRUE(state);
  const auto keepCommanding = [&] {
    ASSERT_TRUE(
        host.send(poseCommand(*state, Eigen::Vector3d::Zero(), transport::Stamp::now()), 1));
  };
  keepCommanding();
  ASSERT_TRUE(host.request(transport::RequestType::kDeactivate, 2));
  ASSERT_TRUE(host.poll(5s, [](const transport::DiagnosticsMessage& d) {
    return d.last_rejection.find("request refused") != std::string::npos;
  })) << "no refusal in the diagnostics";
  keepCommanding();
  std::this_thread::sleep_for(200ms);
  auto now = host.state(1s);
  ASSERT_TRUE(now);
  EXPECT_EQ(now->state, transport::HostState::kActive) << "another process deactivated the arm";

  ASSERT_TRUE(host.request(transport::RequestType::kDeactivate, 1));
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (std::chrono::steady_clock::now() < deadline &&
         (!now || now->state != transport::HostState::kInactive)) {
    std::this_thread::sleep_for(20ms);
    now = host.state(100ms);
  }
  ASSERT_TRUE(now);
  EXPECT_EQ(now->state, transport::HostState::kInactive) << "the holder's own request was refused";
}

/// A tare request reaches the cycle: the simulated arm's wrist sensor, started with an offset,
/// then reads zero at rest, reported as the sensor's, and nothing is refused.
TEST_F(LiveHostInProcess, ATareRequestZeroesTheWristSensor) {
  HostHarness& host = *host_;
  host.setHardwareOptions({"wrench_offset=3,-2,4,0.1,0.2,-0.1"});  // the sensor's own offset
  host.start("tare");
  const auto before = host.state(20s);
  ASSERT_TRUE(before) << "no state from the host";
  EXPECT_EQ(before->contact_wrench_source, transport::WrenchSource::kSensor);
  EXPECT_GT(Eigen::Vector3d(before->contact_wrench[0], before->contact_wrench[1],
                            before->contact_wrench[2])
                .norm(),
            5.0)
      << "the offset shows before the tare";
  ASSERT_TRUE(host.request(transport::RequestType::kTare, 1));
  std::optional<transport::ControllerStateMessage> after;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < deadline) {
    after = host.state(100ms);
    if (after && after->cycle > before->cycle + 200) {
      break;
    }
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_TRUE(after);
  const Eigen::Vector3d force(after->contact_wrench[0], after->contact_wrench[1],
                              after->contact_wrench[2]);
  EXPECT_LT(force.norm(), 0.2) << "the tare did not reach the cycle";
  EXPECT_FALSE(host.poll(500ms, [](const transport::DiagnosticsMessage& d) {
    return d.last_rejection.find("tare") != std::string::npos;
  })) << "the tare was refused";
}

}  // namespace
}  // namespace comply::live_test
