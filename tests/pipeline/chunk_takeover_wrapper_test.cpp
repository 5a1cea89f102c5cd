// A chunk that names its takeover, through the wrapper on the FR3 with the intake's motion limits
// on: it is checked from the reference the cycle will write at its takeover (a chunk continuing
// the running one is accepted there, and the same chunk starting now is refused for the blend it
// would ask), waits for that cycle, and a takeover it cannot have is refused with its reason and
// changes nothing. Wrapper::predict() against the cycles that follow it. A chunk keeping the
// committed prefix joins the curve at its takeover waypoint, between cycles, without a jump.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "comply/pipeline/wrapper.hpp"
#include "resting_fr3.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kHostStart = 500.0;  // s: the host's clock at activation
constexpr double kSpeed_m_per_s = 0.2;

class ChunkTakeoverThroughTheWrapper : public RestingFr3 {
 protected:
  ChunkTakeoverThroughTheWrapper()
      : RestingFr3("frozen_state_timeout_s: 0\ntorque_rate_limit_nm_per_s: " +
                       std::to_string(kNoRateLimit) + "\n",
                   kHostStart) {}

  /// Waypoints every 50 ms from `from_s` to `to_s` (seconds from `origin_s`) along x at 0.2 m/s,
  /// on the line that starts at home at `origin_s`.
  CartesianChunk line(double origin_s, double from_s, double to_s) {
    CartesianChunk c;
    c.stamp_s = ++stamp;
    c.fields = CommandField::kPosition;
    for (double t = from_s; t <= to_s + 1e-9; t += 0.05) {
      ChunkWaypoint<CartesianCommand> waypoint{origin_s + t, CartesianCommand::zero(kFr3Dof)};
      waypoint.command.position = home_position + Eigen::Vector3d(kSpeed_m_per_s * t, 0.0, 0.0);
      waypoint.command.orientation = home_orientation;
      c.waypoints.push_back(waypoint);
    }
    return c;
  }

  double stamp = 0.0;
};

TEST_F(ChunkTakeoverThroughTheWrapper, IsCheckedFromTheReferenceAtItsTakeoverAndWaitsForIt) {
  const double origin_s = hostTime();
  ASSERT_TRUE(wrapper.submitChunk(line(origin_s, 0.0, 1.0), hostTime()).accepted);
  cycles(100);
  // The rest of the line from 0.45 s: starting now, the blend from the reference (2 cm along) to
  // the chunk's lead-in (8 cm along) asks far more than 13 m/s^2.
  const CartesianChunk rest = line(origin_s, 0.45, 1.2);
  const Verdict now = wrapper.submitChunk(rest, hostTime());
  ASSERT_FALSE(now.accepted);
  EXPECT_EQ(now.reason, RejectionReason::kOutOfRange) << now.message;

  // Taking over at its waypoint 1 (0.5 s), where the running chunk's reference is on it.
  CartesianChunk later = line(origin_s, 0.45, 1.2);
  later.takeover_s = later.waypoints[1].time_s;
  const Verdict verdict = wrapper.submitChunk(later, hostTime());
  ASSERT_TRUE(verdict.accepted) << verdict.message;

  // What the cycles will write from now on, asked before they run, then run.
  std::vector<double> times;
  for (int k = 1; k <= 600; ++k) {
    times.push_back(hostTime() + k * kPeriod);
  }
  std::vector<CartesianCommand> predicted;
  ASSERT_TRUE(wrapper.predict(times, hostTime(), predicted));
  ASSERT_EQ(predicted.size(), times.size());
  int took_over_at = -1;
  for (std::size_t k = 0; k < times.size(); ++k) {
    cycles(1);
    for (const ChunkTiming& timing : wrapper.controller().chunks().events()) {
      if (timing.end == ChunkEnd::kTookOver) {
        took_over_at = static_cast<int>(k);
        EXPECT_EQ(timing.waypoints_past, 1) << "waypoint 0 (0.45 s) is past, 1 (0.5 s) is now";
        EXPECT_LT(timing.position_jump, 1e-3) << "it continues the line the reference is on";
      }
    }
    ASSERT_LT((predicted[k].position - reference()).norm(), 1e-12) << k;
  }
  // The request was at 0.5 s from the line's origin; 0.1 s of it had run when it was sent.
  EXPECT_EQ(took_over_at, 399);
}

TEST_F(ChunkTakeoverThroughTheWrapper, AChunkKeepingTheCommittedPrefixJoinsTheCurveBetweenCycles) {
  // A policy at 30 Hz (its steps fall between the 1 ms cycles) on a curve; the next chunk keeps
  // the committed prefix up to its waypoint 4 and then turns elsewhere. It starts at that
  // waypoint's time, not at the cycle after, and there takes the reference's velocity: no jump in
  // position or velocity, whatever its own waypoints imply there.
  const double step_s = 1.0 / 30.0;
  const auto curve = [&](double t) -> Eigen::Vector3d {
    return home_position +
           Eigen::Vector3d(0.05 * std::sin(2.0 * t), 0.03 * (1.0 - std::cos(3.0 * t)), 0.0);
  };
  const double origin_s = hostTime();
  CartesianChunk first;
  first.stamp_s = ++stamp;
  first.fields = CommandField::kPosition;
  for (int k = 0; k < 30; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{origin_s + k * step_s,
                                             CartesianCommand::zero(kFr3Dof)};
    waypoint.command.position = curve(k * step_s);
    waypoint.command.orientation = home_orientation;
    first.waypoints.push_back(waypoint);
  }
  const Verdict started = wrapper.submitChunk(first, hostTime());
  ASSERT_TRUE(started.accepted) << started.message;
  cycles(300);

  const double observation_s = hostTime() - 0.0004;  // between two cycles
  constexpr int kKeep = 4;
  std::vector<double> times;
  for (int k = 0; k < 16; ++k) {
    times.push_back(observation_s + k * step_s);
  }
  std::vector<CartesianCommand> committed;
  ASSERT_TRUE(wrapper.predict(times, hostTime(), committed));
  CartesianChunk next;
  next.stamp_s = ++stamp;
  next.fields = CommandField::kPosition;
  for (int k = 0; k < 16; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{times[k], CartesianCommand::zero(kFr3Dof)};
    const double turned_m = k > kKeep ? 0.002 * (k - kKeep) : 0.0;  // off the curve in z
    waypoint.command.position = committed[k].position + Eigen::Vector3d(0.0, 0.0, turned_m);
    waypoint.command.orientation = home_orientation;
    next.waypoints.push_back(waypoint);
  }
  next.takeover_s = times[kKeep];
  const Verdict verdict = wrapper.submitChunk(next, hostTime());
  ASSERT_TRUE(verdict.accepted) << verdict.message;

  bool took_over = false;
  Eigen::Vector3d last_velocity = Eigen::Map<const Eigen::Vector3d>(law().twist);
  for (int i = 0; i < 200 && !took_over; ++i) {
    cycles(1);
    for (const ChunkTiming& timing : wrapper.controller().chunks().events()) {
      if (timing.end != ChunkEnd::kTookOver) {
        continue;
      }
      took_over = true;
      EXPECT_EQ(timing.takeover_s, timing.requested_takeover_s) << "at its waypoint's time";
      EXPECT_EQ(timing.waypoints_past, kKeep);
      EXPECT_LT(timing.position_jump, 1e-12);
      EXPECT_LT(timing.velocity_jump, 1e-12) << "its waypoint 4 takes the reference's velocity";
      EXPECT_LT(timing.angular_velocity_jump, 1e-12);
    }
    // The reference's velocity moves in the takeover cycle as in any other: by what its
    // acceleration allows, no blend pulling it.
    const Eigen::Vector3d velocity = Eigen::Map<const Eigen::Vector3d>(law().twist);
    EXPECT_LT((velocity - last_velocity).norm(), 1e-3) << i;
    last_velocity = velocity;
  }
  EXPECT_TRUE(took_over);
}

TEST_F(ChunkTakeoverThroughTheWrapper, ATakeoverItCannotHaveIsRefusedAndChangesNothing) {
  const double origin_s = hostTime();
  ASSERT_TRUE(wrapper.submitChunk(line(origin_s, 0.0, 1.0), hostTime()).accepted);
  cycles(10);
  const CommandId in_force = wrapper.controller().idInForce();
  struct Case {
    const char* what;
    double takeover_s;
    RejectionReason reason;
    const char* names;
  };
  const CartesianChunk base = line(origin_s, 0.05, 0.5);
  const std::vector<Case> cases = {
      {"before its first waypoint", base.waypoints.front().time_s - 0.01,
       RejectionReason::kInvalidChunk, "outside its waypoints"},
      {"after its last waypoint", base.waypoints.back().time_s + 0.01,
       RejectionReason::kInvalidChunk, "outside its waypoints"},
      {"infinite", std::numeric_limits<double>::infinity(), RejectionReason::kNonFinite,
       "takeover time is not finite"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    CartesianChunk chunk = base;
    chunk.takeover_s = c.takeover_s;
    const Verdict verdict = wrapper.submitChunk(chunk, hostTime());
    ASSERT_FALSE(verdict.accepted);
    EXPECT_EQ(verdict.reason, c.reason);
    EXPECT_NE(verdict.message.find(c.names), std::string::npos) << verdict.message;
  }
  // Further ahead than a chunk may start: 1.5 s.
  CartesianChunk far = line(origin_s, 0.05, 2.0);
  far.takeover_s = far.waypoints.back().time_s;
  const Verdict verdict = wrapper.submitChunk(far, hostTime());
  ASSERT_FALSE(verdict.accepted);
  EXPECT_NE(verdict.message.find("validation.max_stamp_lead_s"), std::string::npos)
      << verdict.message;
  cycles(1);
  EXPECT_EQ(wrapper.controller().idInForce(), in_force) << "a refused chunk changed nothing";
  EXPECT_FALSE(wrapper.controller().chunks().waiting());
}

}  // namespace
}  // namespace comply::pipeline::test
