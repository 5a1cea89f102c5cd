// A force axis in free space, on every robot: 10 N upwards along z with the position at the start
// (as docs/contact-wrench.md advises), commands streamed while the arm climbs. Before the force
// axes were left out of the jump check, every command past 10 cm was refused as pose_jump, and
// 0.5 s later the watchdog released the axis into the 3000 N/m spring 15 cm away: the TCP snapped
// back at 1.29 m/s, past the joints' velocity limits, into FAULT. Now every command is accepted,
// and when the sender stops the watchdog ends the axis holding the arm where it is: from the
// timeout on the TCP stays within 1 cm of where it was and below 0.2 m/s, no joint ever exceeds
// 0.8 of its URDF velocity limit, and nothing FAULTs. A force target or feedforward of 1e4 N is
// refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

constexpr double kClimbM = 0.13;       // stop sending once the TCP is this far above its start
constexpr double kClimbLimitS = 15.0;  // and at the latest after this long
constexpr double kAfterS = 1.5;        // run on after the sender stops (command_timeout_s 0.5)
constexpr int kSendEvery = 20;         // cycles between commands

struct ReleaseResult {
  int accepted = 0;
  int refused = 0;
  std::string last_refusal;
  double climbed_m = 0.0;          ///< above the start when the sender stopped
  bool timed_out = false;          ///< the watchdog fired
  double drift_m = 0.0;            ///< furthest from the TCP's position at the timeout, after it
  double speed_after = 0.0;        ///< largest TCP speed after the timeout [m/s]
  double joint_speed_ratio = 0.0;  ///< largest |dq| / URDF velocity limit, whole run
  pipeline::DiagnosticsSnapshot diagnostics;
  pipeline::Verdict huge_target;
  pipeline::Verdict huge_feedforward;
};

CartesianCommand pushUp(const MeasuredPose& start, int dof, double stamp_s, double force_n) {
  CartesianCommand command = CartesianCommand::zero(dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition | CommandField::kForce;
  command.position = start.tcp_position;
  command.orientation = start.tcp_orientation;
  command.force_axes[2] = 1.0;
  command.wrench_target[2] = force_n;
  return command;
}

ReleaseResult climbAndStop(const std::string& robot) {
  const pipeline::WrapperConfig config = simCartesianConfig(robot);
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  pipeline::CartesianWrapper wrapper(config);
  const int dof = wrapper.dof();
  const model::Model& model = wrapper.controller().model();
  const double period = plant.controlPeriod();
  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  const MeasuredPose start = wrapper.measuredPose();
  ReleaseResult result;
  // 1e4 N: refused before anything moves.
  result.huge_target = wrapper.submit(pushUp(start, dof, 0.5, 1e4));
  CartesianCommand feedforward = CartesianCommand::zero(dof);
  feedforward.stamp_s = 0.5;
  feedforward.fields = CommandField::kWrenchFeedforward;
  feedforward.wrench_feedforward[2] = 1e4;
  result.huge_feedforward = wrapper.submit(feedforward);

  JointVector torque = JointVector::Zero(dof);
  Eigen::Vector3d previous = start.tcp_position;
  Eigen::Vector3d at_timeout = Eigen::Vector3d::Zero();
  bool sending = true;
  int stop_cycle = static_cast<int>(kClimbLimitS / period);
  for (int cycle = 0; cycle < stop_cycle + static_cast<int>(kAfterS / period); ++cycle) {
    const double time_s = cycle * period;
    if (sending && cycle % kSendEvery == 0) {
      const pipeline::Verdict verdict = wrapper.submit(pushUp(start, dof, 1.0 + time_s, 10.0));
      verdict.accepted ? ++result.accepted : ++result.refused;
      if (!verdict.accepted) {
        result.last_refusal = verdict.message;
      }
    }
    plant.read(state);
    wrapper.update(state, period, {torque.data(), static_cast<std::size_t>(dof)});
    plant.write({torque.data(), static_cast<std::size_t>(dof)});
    plant.step();
    const Eigen::Vector3d tcp = wrapper.measuredPose().tcp_position;
    if (sending && (tcp.z() - start.tcp_position.z() > kClimbM || cycle + 1 >= stop_cycle)) {
      sending = false;
      stop_cycle = cycle + 1;
      result.climbed_m = tcp.z() - start.tcp_position.z();
    }
    if (!result.timed_out && wrapper.diagnostics().watchdog_timeouts > 0) {
      result.timed_out = true;
      at_timeout = tcp;
    } else if (result.timed_out) {
      result.drift_m = std::max(result.drift_m, (tcp - at_timeout).norm());
      result.speed_after = std::max(result.speed_after, (tcp - previous).norm() / period);
    }
    previous = tcp;
    for (int i = 0; i < dof; ++i) {
      result.joint_speed_ratio = std::max(result.joint_speed_ratio,
                                          std::abs(state.velocity[i]) / model.limits(i).velocity);
    }
  }
  result.diagnostics = wrapper.diagnostics();
  return result;
}

class ForceAxisRelease : public ::testing::TestWithParam<std::string> {};

TEST_P(ForceAxisRelease, AFreeSpaceForceAxisEndsHoldingTheArmWhereItIs) {
  const ReleaseResult run = climbAndStop(GetParam());
  EXPECT_FALSE(run.huge_target.accepted);
  EXPECT_EQ(run.huge_target.reason, pipeline::RejectionReason::kOutOfRange)
      << run.huge_target.message;
  EXPECT_NE(run.huge_target.message.find(GetParam()), std::string::npos) << run.huge_target.message;
  EXPECT_FALSE(run.huge_feedforward.accepted);
  EXPECT_EQ(run.huge_feedforward.reason, pipeline::RejectionReason::kOutOfRange)
      << run.huge_feedforward.message;

  EXPECT_EQ(run.refused, 0) << run.last_refusal;
  EXPECT_GT(run.accepted, 0);
  EXPECT_GT(run.climbed_m, 0.1) << "the arm climbed past the jump limit, commands accepted";
  ASSERT_TRUE(run.timed_out);
  EXPECT_LT(run.drift_m, 0.01) << "held where it was at the timeout";
  EXPECT_LT(run.speed_after, 0.2);
  EXPECT_LT(run.joint_speed_ratio, 0.8);
  EXPECT_NE(run.diagnostics.state, pipeline::WrapperState::kFault) << run.diagnostics.last_fault;
  EXPECT_EQ(run.diagnostics.faults, 0U) << run.diagnostics.last_fault;
  RecordProperty(GetParam(), "climbed " + std::to_string(run.climbed_m) + " m, drift " +
                                 std::to_string(run.drift_m) + " m, speed after " +
                                 std::to_string(run.speed_after) + " m/s, joint speed ratio " +
                                 std::to_string(run.joint_speed_ratio) + "; " +
                                 run.huge_target.message);
}

INSTANTIATE_TEST_SUITE_P(Robots, ForceAxisRelease, ::testing::ValuesIn(model::availableRobots()),
                         [](const auto& test) { return test.param; });

}  // namespace
}  // namespace comply::testing
