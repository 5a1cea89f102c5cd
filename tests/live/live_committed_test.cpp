// The live host's answer to a committed request (include/comply/host/committed_answers.hpp),
// through the wrapper on the FR3 with the host's clock on the cycle's grid: the answer, made
// between two cycles, is what the cycles then write at the times asked for (within 1e-9 m), each
// entry stamped with its time; a request it cannot answer is refused naming the field, and one of
// the joint controller fills the joint list.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "comply/host/committed_answers.hpp"
#include "resting_fr3.hpp"
#include "wrapper_support.hpp"

namespace comply::host {
namespace {

using pipeline::test::kFr3Dof;
using pipeline::test::kPeriod;

constexpr std::int64_t kHostStartNs = 500'000'000'000;  // the host's clock at activation: 500 s
constexpr std::int64_t kPeriodNs = 1'000'000;

class CommittedAnswerThroughTheWrapper : public pipeline::test::RestingFr3 {
 protected:
  CommittedAnswerThroughTheWrapper()
      : RestingFr3("frozen_state_timeout_s: 0\ntorque_rate_limit_nm_per_s: " +
                       std::to_string(pipeline::test::kNoRateLimit) + "\n",
                   1e-9 * static_cast<double>(kHostStartNs)) {}

  /// The host's clock now [ns], exactly on the cycle's grid.
  [[nodiscard]] std::int64_t hostNanoseconds() const {
    return kHostStartNs + cycle_count * kPeriodNs;
  }

  /// Waypoints every 50 ms for 1 s along x at 0.2 m/s from home, from the host's clock now.
  CartesianChunk line() {
    CartesianChunk chunk;
    chunk.stamp_s = 1.0;
    chunk.fields = CommandField::kPosition;
    for (int k = 0; k <= 20; ++k) {
      const double t = 0.05 * k;
      ChunkWaypoint<CartesianCommand> waypoint{hostTime() + t, CartesianCommand::zero(kFr3Dof)};
      waypoint.command.position = home_position + Eigen::Vector3d(0.2 * t, 0.0, 0.0);
      waypoint.command.orientation = home_orientation;
      chunk.waypoints.push_back(waypoint);
    }
    return chunk;
  }

  static transport::Sample<transport::CommittedRequestMessage> request(std::int64_t observation_ns,
                                                                       double dt_s,
                                                                       std::uint32_t count) {
    transport::Sample<transport::CommittedRequestMessage> sample;
    sample.message.header.stamp = {1, 2};
    sample.message.observation = transport::Stamp::fromNanoseconds(observation_ns);
    sample.message.dt_s = dt_s;
    sample.message.count = count;
    sample.sender = {9, 8, 7};
    return sample;
  }

  CommittedAnswers<CartesianCommand> answers{wrapper, "fr3_link0"};
};

TEST_F(CommittedAnswerThroughTheWrapper, IsWhatTheCyclesThenWriteAtTheTimesAskedFor) {
  ASSERT_TRUE(wrapper.submitChunk(line(), hostTime()).accepted);
  cycles(120);  // past the blend onto the chunk
  // From the next cycle on, every 4th cycle: 64 times over 0.256 s.
  constexpr std::uint32_t kCount = 64;
  constexpr int kEvery = 4;
  const std::int64_t observation_ns = hostNanoseconds() + kPeriodNs;
  const transport::CommittedMessage& answer =
      answers.answer(request(observation_ns, kEvery * kPeriod, kCount), hostNanoseconds());
  ASSERT_TRUE(answer.answered) << answer.message;
  EXPECT_TRUE(answer.known);
  EXPECT_EQ(answer.request_stamp, (transport::Stamp{1, 2}));
  EXPECT_EQ(answer.sender, (transport::Gid{9, 8, 7}));
  EXPECT_EQ(answer.header.stamp.nanoseconds(), hostNanoseconds());
  EXPECT_EQ(answer.header.frame_id, "fr3_link0");
  EXPECT_EQ(answer.command_kind, transport::WireCommandKind::kCartesian);
  EXPECT_TRUE(answer.joint.empty());
  ASSERT_EQ(answer.cartesian.size(), kCount);
  const transport::CommittedMessage copy = answer;  // valid until the next answer
  for (std::uint32_t k = 0; k < kCount; ++k) {
    cycles(k == 0 ? 1 : kEvery);
    const transport::CartesianCommandMessage& entry = copy.cartesian[k];
    EXPECT_EQ(entry.header.stamp.nanoseconds(), hostNanoseconds()) << k;
    EXPECT_LT((entry.command.position - reference()).norm(), 1e-9) << k;
    EXPECT_LT(entry.command.orientation.angularDistance(home_orientation), 1e-9) << k;
  }
  // The reference moved along the line meanwhile: 0.2 m/s for 0.252 s.
  EXPECT_NEAR(
      copy.cartesian.back().command.position.x() - copy.cartesian.front().command.position.x(),
      0.2 * 0.252, 1e-6);
}

TEST_F(CommittedAnswerThroughTheWrapper, RefusesARequestItCannotAnswerNamingTheField) {
  const std::int64_t now_ns = hostNanoseconds();
  struct Case {
    transport::Sample<transport::CommittedRequestMessage> sample;
    const char* names;
  };
  Case malformed{request(now_ns, 0.01, 4), "header.frame_id is 300 bytes"};
  malformed.sample.refuse(transport::Reason::kTooLarge, "header.frame_id is 300 bytes, more");
  Case bad_nanosec{request(now_ns, 0.01, 4), "observation.nanosec 1000000000 is out of range"};
  bad_nanosec.sample.message.observation.nanosec = 1'000'000'000;
  const Case cases[] = {
      malformed,
      bad_nanosec,
      {request(0, 0.01, 4), "observation is not given"},
      {request(now_ns, 0.0, 4), "dt is 0: the step between the times [s] is finite and > 0"},
      {request(now_ns, -0.01, 4), "dt is -0.01"},
      {request(now_ns, std::numeric_limits<double>::quiet_NaN(), 4), "dt is nan"},
      {request(now_ns, 0.01, 0), "count is 0: 1 to 64 times"},
      {request(now_ns, 0.01, 65), "count is 65: 1 to 64 times"},
      {request(now_ns, 1e300, 2), "past what a stamp holds"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.names);
    const transport::CommittedMessage& answer = answers.answer(c.sample, now_ns);
    EXPECT_FALSE(answer.answered);
    EXPECT_FALSE(answer.known);
    EXPECT_NE(answer.message.find(c.names), std::string::npos) << answer.message;
    EXPECT_TRUE(answer.cartesian.empty());
    EXPECT_EQ(answer.request_stamp, c.sample.message.header.stamp) << "its sender finds it";
  }
  // At the bound: answered.
  EXPECT_TRUE(answers.answer(request(now_ns, 0.01, 64), now_ns).answered);
}

TEST(CommittedAnswerOfTheJointController, FillsTheJointList) {
  pipeline::JointWrapper wrapper(pipeline::test::fr3Config(pipeline::test::kJointImpedancePlugin));
  const JointState state =
      pipeline::test::restingAt(wrapper.controller(), pipeline::test::fr3Home());
  wrapper.activate(state);
  pipeline::test::TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), pipeline::CycleStatus::kOk);
  CommittedAnswers<JointCommand> answers(wrapper, "base");
  transport::Sample<transport::CommittedRequestMessage> sample;
  sample.message.observation = {100, 0};
  sample.message.dt_s = 0.1;
  sample.message.count = 3;
  const transport::CommittedMessage& answer = answers.answer(sample, 100'000'000'000);
  ASSERT_TRUE(answer.answered) << answer.message;
  EXPECT_EQ(answer.command_kind, transport::WireCommandKind::kJoint);
  EXPECT_TRUE(answer.cartesian.empty());
  ASSERT_EQ(answer.joint.size(), 3U);
  for (std::size_t k = 0; k < 3; ++k) {
    // No chunk plays: the reference in force, the measured pose it was seeded with, at each time.
    EXPECT_EQ(answer.joint[k].header.stamp,
              (transport::Stamp{100, static_cast<std::uint32_t>(100'000'000 * k)}));
    EXPECT_LT((answer.joint[k].command.position - pipeline::test::fr3Home()).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace comply::host
