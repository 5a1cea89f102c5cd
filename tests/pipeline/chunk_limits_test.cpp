// What a chunk may ask of the arm (validateChunk's motion and time checks): the red team's chunks
// (a 10 m/s twist on waypoints 5 mm apart; a 0 / 9 cm zigzag every 10 ms) are refused naming the
// waypoint, the number and the limit; so are a curve that overshoots its chords, a curve or a blend
// that accelerates too hard, a joint chunk too fast for a joint, and a chunk that starts more than
// validation.max_stamp_lead_s ahead. A chunk within the limits passes.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "comply/pipeline/command_validation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline::test {
namespace {

constexpr int kArmDof = 7;
constexpr double kNow = 100.0;  // s: the host's clock
const Eigen::Vector3d kHome(0.4, 0.0, 0.5);

MeasuredPose measuredAtHome() {
  MeasuredPose pose;
  pose.tcp_position = kHome;
  pose.tcp_orientation = Eigen::Quaterniond::Identity();
  pose.position = JointVector::Zero(kArmDof);
  pose.valid = true;
  return pose;
}

/// The governor's defaults and the default blend.
ChunkLimits armLimits() {
  return {.tcp_speed_m_per_s = 1.0, .tcp_angular_speed_rad_per_s = 2.5, .blend_time_s = 0.1};
}

/// Waypoints at home plus `x[k]` along x, the first at `kNow + first_s`, `spacing_s` apart.
CartesianChunk alongX(const std::vector<double>& x, double first_s, double spacing_s) {
  CartesianChunk chunk;
  chunk.stamp_s = kNow;
  chunk.fields = CommandField::kPosition;
  for (std::size_t k = 0; k < x.size(); ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{kNow + first_s + spacing_s * static_cast<double>(k),
                                             CartesianCommand::zero(kArmDof)};
    waypoint.command.position = kHome + Eigen::Vector3d(x[k], 0.0, 0.0);
    chunk.waypoints.push_back(waypoint);
  }
  return chunk;
}

/// The reference in force: at `position`, at rest.
CommandBus restingAt(const Eigen::Vector3d& position) {
  CartesianCommand command = CartesianCommand::zero(kArmDof);
  command.position = position;
  return schema::toBus(command, kArmDof);
}

const CommandBus kRestingAtHome = restingAt(kHome);

/// validateChunk at kNow against the measured home pose, with the reference in force `in_force`
/// (null: no blend checked).
Verdict check(CartesianChunk chunk, const CommandBus* in_force = &kRestingAtHome,
              const ValidationConfig& limits = defaultConfig().validation,
              const ChunkLimits& arm = armLimits()) {
  return validateChunk(chunk, limits, kArmDof, measuredAtHome(),
                       -std::numeric_limits<double>::infinity(), kNow, arm, in_force);
}

void expectRefused(const Verdict& verdict, RejectionReason reason, const std::string& names) {
  EXPECT_FALSE(verdict.accepted);
  EXPECT_EQ(verdict.reason, reason) << verdict.message;
  EXPECT_NE(verdict.message.find(names), std::string::npos) << verdict.message;
}

TEST(ChunkLimits, AChunkWithinTheLimitsIsAccepted) {
  // 0.2 m/s along x from the measured pose, starting 50 ms from now.
  const Verdict verdict = check(alongX({0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07}, 0.05, 0.05));
  EXPECT_TRUE(verdict.accepted) << verdict.message;
}

TEST(ChunkLimits, TheRedTeamsTwistOnWaypoints5MmApartIsRefused) {
  CartesianChunk chunk = alongX({0, 0.005, 0.01, 0.015, 0.02}, 0.01, 0.01);
  chunk.fields = chunk.fields | CommandField::kVelocity;
  for (auto& waypoint : chunk.waypoints) {
    waypoint.command.twist << 10.0, 0, 0, 0, 0, 0;  // within the 100 m/s field limit
  }
  expectRefused(check(chunk), RejectionReason::kOutOfRange,
                "waypoint 0's velocity: 10 m/s, above 1 m/s (governor.tcp_speed_m_per_s)");
}

TEST(ChunkLimits, TheRedTeamsZigzagIsRefusedByItsChords) {
  // 0 / 9 cm every 10 ms: each waypoint within the 0.1 m jump limit of the one before.
  expectRefused(check(alongX({0, 0.09, 0, 0.09, 0, 0.09, 0, 0.09}, 0.01, 0.01)),
                RejectionReason::kOutOfRange,
                "waypoint 0 to 1 in 0.01 s: 9 m/s, above 1 m/s (governor.tcp_speed_m_per_s)");
}

TEST(ChunkLimits, ACurveThatOvershootsItsChordsIsRefused) {
  // Chord 0.95 m/s, both ends given 0.75 m/s: the Hermite segment peaks at 1.5 x 0.95 - 0.25 x 1.5
  // = 1.05 m/s halfway (and accelerates 6 x 0.2 / 0.1 = 12 m/s^2, within the limit).
  CartesianChunk chunk = alongX({0, 0.095}, 0.0, 0.1);
  chunk.fields = chunk.fields | CommandField::kVelocity;
  chunk.waypoints[0].command.twist << 0.75, 0, 0, 0, 0, 0;
  chunk.waypoints[1].command.twist << 0.75, 0, 0, 0, 0, 0;
  expectRefused(check(chunk, nullptr), RejectionReason::kOutOfRange,
                "the curve from waypoint 0 to 1 reaches 1.05 m/s, above 1 m/s "
                "(governor.tcp_speed_m_per_s)");
}

TEST(ChunkLimits, ACurveThatAcceleratesTooHardIsRefused) {
  // 1 cm out and back every 50 ms: chords of 0.2 m/s, but the first segment leaves at 0.2 m/s and
  // arrives at rest, (-6 x 0.01 + 2 x 0.05 x 0.2) / 0.05^2 = -16 m/s^2 at its end. With no
  // acceleration limit it passes.
  const CartesianChunk chunk = alongX({0, 0.01, 0, 0.01, 0, 0.01, 0}, 0.0, 0.05);
  expectRefused(check(chunk, nullptr), RejectionReason::kOutOfRange,
                "the curve from waypoint 0 to 1 reaches 16 m/s^2, above 13 m/s^2 "
                "(validation.max_chunk_acceleration_m_per_s2)");
  ValidationConfig unbounded = defaultConfig().validation;
  unbounded.max_chunk_acceleration_m_per_s2 = 0.0;
  const Verdict verdict = check(chunk, nullptr, unbounded);
  EXPECT_TRUE(verdict.accepted) << verdict.message;
}

TEST(ChunkLimits, TheBlendFromAFarReferenceIsRefused) {
  // The chunk is at the measured pose; the reference in force 8 cm away (a command the arm has not
  // followed): the blend's 0.1 s would take it over at 1.875 x 0.08 / 0.1 = 1.5 m/s.
  const CartesianChunk chunk = alongX({0, 0, 0}, 0.0, 0.1);
  const CommandBus far = restingAt(kHome + Eigen::Vector3d(0, 0.08, 0));
  expectRefused(check(chunk, &far), RejectionReason::kOutOfRange,
                "with the blend from the reference in force (chunk_blend_time_s 0.1 s)");
  const CommandBus near = restingAt(kHome + Eigen::Vector3d(0, 0.005, 0));
  const Verdict verdict = check(chunk, &near);
  EXPECT_TRUE(verdict.accepted) << verdict.message;
}

TEST(ChunkLimits, TheMeasuredPoseToTheFirstWaypointAheadIsAChord) {
  // 8 cm from the arm (within the jump limit), due in 0.05 s, without a blend: 1.6 m/s.
  ChunkLimits no_blend = armLimits();
  no_blend.blend_time_s = 0.0;
  const CartesianChunk chunk = alongX({0.08, 0.08}, 0.05, 0.1);
  expectRefused(check(chunk, nullptr, defaultConfig().validation, no_blend),
                RejectionReason::kOutOfRange,
                "the measured pose to waypoint 0 in 0.05 s: 1.6 m/s, above 1 m/s");
  // With the default blend the reference takes at least 0.1 s to get there (0.8 m/s); what the
  // blend itself asks is the curve's check.
  const Verdict verdict = check(chunk, nullptr);
  EXPECT_TRUE(verdict.accepted) << verdict.message;
}

TEST(ChunkLimits, AChunkStartingFurtherAheadThanTheStampLeadIsRefused) {
  for (const double ahead_s : {5.0, 3600.0}) {
    SCOPED_TRACE(ahead_s);
    expectRefused(check(alongX({0, 0.01}, ahead_s, 0.1)), RejectionReason::kInvalidChunk,
                  "ahead of the host's clock (at most 1 s: validation.max_stamp_lead_s;");
  }
  // 1e9 s ahead (past 2038, where int32 seconds end): refused as ahead, naming the time as sent
  // (it once wrapped into the past and was refused as due 3.29e9 s ago).
  expectRefused(check(alongX({0, 0.01}, 1e9, 0.1)), RejectionReason::kInvalidChunk,
                "waypoint 0 at 1000000100.000 s is due 1e+09 s ahead of the host's clock (at most "
                "1 s: validation.max_stamp_lead_s; the host's clock is at 100.000 s)");
  const Verdict within = check(alongX({0, 0.01}, 0.9, 0.1));
  EXPECT_TRUE(within.accepted) << within.message;
}

TEST(ChunkLimits, AJointChunkIsHeldToEachJointsShareOfItsLimit) {
  constexpr int kJoints = 3;
  JointChunk chunk;
  chunk.stamp_s = kNow;
  chunk.fields = CommandField::kPosition;
  for (int k = 0; k < 4; ++k) {
    ChunkWaypoint<JointCommand> waypoint{kNow + 0.1 * k, JointCommand::zero(kJoints)};
    waypoint.command.position = JointVector::Zero(kJoints);
    waypoint.command.position[2] = 0.2 * k;  // 2 rad/s on joint 2
    chunk.waypoints.push_back(waypoint);
  }
  MeasuredPose measured;
  measured.position = JointVector::Zero(kJoints);
  measured.valid = true;
  ChunkLimits limits;
  limits.joint_speed = JointVector::Constant(kJoints, 0.8 * 2.0);  // 0.8 x a 2 rad/s limit
  ValidationConfig validation = defaultConfig().validation;
  validation.max_chunk_joint_acceleration_rad_per_s2 = 0.0;
  JointChunk fast = chunk;
  const Verdict verdict = validateChunk(fast, validation, kJoints, measured,
                                        -std::numeric_limits<double>::infinity(), kNow, limits);
  expectRefused(verdict, RejectionReason::kOutOfRange,
                "waypoint 0 to 1 in 0.1 s: joint 3 at 2 rad/s, above 1.6 rad/s");
  limits.joint_speed[2] = 0.8 * 4.0;  // its last segment peaks at 4/3 of 2 rad/s
  JointChunk slow = chunk;
  const Verdict accepted = validateChunk(slow, validation, kJoints, measured,
                                         -std::numeric_limits<double>::infinity(), kNow, limits);
  EXPECT_TRUE(accepted.accepted) << accepted.message;
}

}  // namespace
}  // namespace comply::pipeline::test
