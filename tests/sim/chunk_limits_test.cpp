// Chunks bounded by what the arm can do, on every robot: the red team's chunks (a 10 m/s twist on
// waypoints 5 mm apart, which whipped the FR3's TCP 21.6 cm at 1.45 x a joint's velocity limit;
// a 0 / 9 cm zigzag every 10 ms, 17.5 cm at 1.15 x) are refused at the intake, and a legal chunk
// at 0.45 m/s plays with every joint below governor.velocity_fraction of its URDF limit.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "governed_arm.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// Waypoints from the measured pose, `offsets_m[k]` along y, the first `first_s` after `now_s`,
/// `spacing_s` apart; with `twist_m_per_s` along y as every waypoint's velocity when not 0.
CartesianChunk alongY(const MeasuredPose& measured, double now_s,
                      const std::vector<double>& offsets_m, double first_s, double spacing_s,
                      double stamp_s, double twist_m_per_s = 0.0) {
  CartesianChunk chunk;
  chunk.stamp_s = stamp_s;
  chunk.fields = CommandField::kPosition;
  if (twist_m_per_s != 0.0) {
    chunk.fields = chunk.fields | CommandField::kVelocity;
  }
  const int dof = static_cast<int>(measured.position.size());
  for (std::size_t k = 0; k < offsets_m.size(); ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{now_s + first_s + spacing_s * static_cast<double>(k),
                                             CartesianCommand::zero(dof)};
    waypoint.command.position = measured.tcp_position + Eigen::Vector3d(0, offsets_m[k], 0);
    waypoint.command.orientation = measured.tcp_orientation;
    waypoint.command.twist << 0, twist_m_per_s, 0, 0, 0, 0;
    chunk.waypoints.push_back(waypoint);
  }
  return chunk;
}

/// A minimum-jerk move of `distance_m` over `duration_s`, sampled every `spacing_s`.
std::vector<double> minimumJerk(double distance_m, double duration_s, double spacing_s) {
  std::vector<double> offsets;
  const int count = static_cast<int>(std::lround(duration_s / spacing_s));
  for (int k = 0; k <= count; ++k) {
    const double s = static_cast<double>(k) / count;
    offsets.push_back(distance_m *
                      (10 * std::pow(s, 3) - 15 * std::pow(s, 4) + 6 * std::pow(s, 5)));
  }
  return offsets;
}

class ChunkLimitsOn : public ::testing::TestWithParam<std::string> {};

TEST_P(ChunkLimitsOn, TheRedTeamsChunksAreRefusedAndALegalOnePlaysWithinTheJointSpeeds) {
  const pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  Arm<> arm(config);  // keeps the largest |dq| / URDF velocity limit
  pipeline::CartesianWrapper& wrapper = arm.wrapper;
  const auto run = [&arm](int cycles) {
    for (int cycle = 0; cycle < cycles; ++cycle) {
      arm.cycle();
    }
  };
  run(300);  // settle

  const MeasuredPose start = wrapper.measuredPose();
  const double now_s = start.time_s;  // the host's clock is the controller's here
  const pipeline::Verdict whip = wrapper.submitChunk(
      alongY(start, now_s, {0, 0.005, 0.01, 0.015, 0.02}, 0.01, 0.01, 1.0, 10.0), now_s);
  EXPECT_FALSE(whip.accepted);
  EXPECT_EQ(whip.reason, pipeline::RejectionReason::kOutOfRange) << whip.message;
  EXPECT_NE(whip.message.find("waypoint 0's velocity: 10 m/s"), std::string::npos) << whip.message;
  const pipeline::Verdict zigzag = wrapper.submitChunk(
      alongY(start, now_s, {0, 0.09, 0, 0.09, 0, 0.09, 0, 0.09}, 0.01, 0.01, 2.0), now_s);
  EXPECT_FALSE(zigzag.accepted);
  EXPECT_EQ(zigzag.reason, pipeline::RejectionReason::kOutOfRange) << zigzag.message;
  EXPECT_NE(zigzag.message.find("waypoint 0 to 1"), std::string::npos) << zigzag.message;

  // 12 cm in 0.5 s, waypoints 50 ms apart: 0.45 m/s at its fastest.
  const std::vector<double> legal = minimumJerk(0.12, 0.5, 0.05);
  const pipeline::Verdict played =
      wrapper.submitChunk(alongY(start, now_s, legal, 0.05, 0.05, 3.0), now_s);
  ASSERT_TRUE(played.accepted) << played.message;
  arm.worst_ratio = 0.0;
  run(1000);
  EXPECT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kActive)
      << wrapper.diagnostics().last_fault;
  EXPECT_LT(arm.worst_ratio, config.governor.velocity_fraction);
  const double travelled = wrapper.measuredPose().tcp_position.y() - start.tcp_position.y();
  EXPECT_NEAR(travelled, 0.12, 0.01) << "the legal chunk did not play";
  RecordProperty(GetParam() + "_worst_speed_ratio", std::to_string(arm.worst_ratio));
}

INSTANTIATE_TEST_SUITE_P(Robots, ChunkLimitsOn, ::testing::ValuesIn(model::availableRobots()),
                         [](const auto& test) { return test.param; });

}  // namespace
}  // namespace comply::testing
