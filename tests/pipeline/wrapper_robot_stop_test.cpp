// The robot's own stop (JointState::robot_stop: a protective stop, its program ended, the link
// lost) is a FAULT that names it, and no reset leaves FAULT while the robot says it is stopped.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

class RobotStop : public ::testing::Test {
 protected:
  RobotStop() : wrapper(fr3Config(kJointImpedancePlugin)) {}

  void SetUp() override {
    state = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(state);
  }

  CycleStatus cycle(const JointState& measured) {
    return wrapper.update(measured, kPeriod, torque.span());
  }

  /// The end of the reset the last cycle took.
  ResetResult::End lastReset() {
    ResetResult result;
    EXPECT_TRUE(wrapper.controller().takeResetResult(result));
    return result.end;
  }

  JointWrapper wrapper;
  JointState state;
  TorqueBuffer torque;
};

TEST_F(RobotStop, IsAFaultNamingTheRobotsReason) {
  ASSERT_EQ(cycle(state), CycleStatus::kOk);
  JointState stopped = state;
  stopped.robot_stop = "protective stop";
  EXPECT_EQ(cycle(stopped), CycleStatus::kFault);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.faults, 1U);
  EXPECT_EQ(diagnostics.last_fault, "robot: protective stop");
  // The hold is computed from the state the robot still sends: gravity there.
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), state.position), 1e-6);
}

TEST_F(RobotStop, NamesTheStopRatherThanTheStreamThatStoodStillAfterIt) {
  JointState lost = state;
  lost.robot_stop = "the link to the robot is lost";
  lost.sequence_valid = true;
  for (int i = 0; i < 500; ++i) {  // the counter stands still for 0.5 s
    ASSERT_EQ(cycle(lost), CycleStatus::kFault);
  }
  EXPECT_EQ(wrapper.diagnostics().faults, 1U);
  EXPECT_EQ(wrapper.diagnostics().last_fault, "robot: the link to the robot is lost");
}

TEST_F(RobotStop, NoResetLeavesFaultWhileTheRobotIsStopped) {
  JointState stopped = state;
  stopped.robot_stop = "protective stop";
  ASSERT_EQ(cycle(stopped), CycleStatus::kFault);
  wrapper.reset();
  EXPECT_EQ(cycle(stopped), CycleStatus::kFault);
  EXPECT_EQ(lastReset(), ResetResult::End::kRobotStopped);
  // The robot runs again (its stop cleared by its user): FAULT stays until a reset asks...
  EXPECT_EQ(cycle(state), CycleStatus::kFault);
  EXPECT_EQ(cycle(state), CycleStatus::kFault);
  // ...and the reset refused before is not carried over to now.
  wrapper.reset();
  EXPECT_EQ(cycle(state), CycleStatus::kOk);
  EXPECT_EQ(lastReset(), ResetResult::End::kLeftFault);
  EXPECT_EQ(wrapper.diagnostics().faults, 1U);
}

// Admittance: while the robot is stopped the arm may be moved by other means (jogged, guided by
// hand); the FAULT's hold follows it, so that when the robot takes commands again the drives are
// not sent back to where the FAULT began.
TEST(RobotStopAdmittance, TheHoldFollowsTheArmWhileTheRobotIsStopped) {
  JointWrapper wrapper(fr3Config(kJointImpedancePlugin, "output:\n  mode: position\n"));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  ActuatorCommand command;
  command.resize(kFr3Dof);
  ASSERT_TRUE(wrapper.cycle(state, kPeriod, command));
  JointState stopped = state;
  stopped.robot_stop = "protective stop";
  ASSERT_TRUE(wrapper.cycle(stopped, kPeriod, command));
  ASSERT_EQ(wrapper.diagnostics().state, WrapperState::kFault);
  stopped.position[1] += 0.1;  // moved by hand while stopped
  ASSERT_TRUE(wrapper.cycle(stopped, kPeriod, command));
  EXPECT_NEAR(command.position[1], stopped.position[1], 1e-12);
  // Running again, still in FAULT: held where the arm is, not where the FAULT began.
  JointState running = stopped;
  running.robot_stop = nullptr;
  ASSERT_TRUE(wrapper.cycle(running, kPeriod, command));
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kFault);
  EXPECT_NEAR(command.position[1], stopped.position[1], 1e-12);
  EXPECT_GT(std::abs(command.position[1] - state.position[1]), 0.09);
}

}  // namespace
}  // namespace comply::pipeline::test
