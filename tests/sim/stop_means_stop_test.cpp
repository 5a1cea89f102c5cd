// Stop means stop, on every robot: an accepted command cannot drive a joint past the governor's
// share of its URDF speed, a FAULT brings a moving arm to rest, and a reset holds the measured
// pose. Before the motion governor and the controlled stop, a 1e4 N/m step of 5 cm ended in an
// overspeed FAULT 23-123 ms late at 1.16x (FR3) to 2.24x (UR5e) the joints' limits, the FAULT hold
// (gravity and 5 N m s/rad) let the arm coast 34 cm (iiwa14) to 60 cm (FR3), and a reset put the
// faulted target back in force: the FR3's TCP was flung 67 cm at 1.5x.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "governed_arm.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

class StopMeansStop : public ::testing::TestWithParam<std::string> {};

// Finding 1 (prevent): 1e4 N/m on the jump limit's 10 cm, and 4000 N m/rad on a 0.5 rad turn.
TEST_P(StopMeansStop, StiffStepsStayBelowTheGovernedSpeed) {
  const pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  for (const double angle : {0.0, 0.5}) {
    SCOPED_TRACE(GetParam() + (angle == 0.0 ? ": 10 cm at 1e4 N/m" : ": 0.5 rad at 4000 N m/rad"));
    Arm<> arm(config);
    const CartesianCommand step = stiffStep(
        arm, angle == 0.0 ? Eigen::Vector3d(0.1, 0.0, 0.0) : Eigen::Vector3d::Zero(), angle);
    const pipeline::Verdict verdict = arm.wrapper.submit(step);
    if (!verdict.accepted) {
      // The gain bound refused it with the arm's numbers: nothing reached the arm.
      EXPECT_NE(verdict.message.find("invalid_gains"), std::string::npos) << verdict.message;
      continue;
    }
    for (int cycle = 0; cycle < 3000; ++cycle) {
      arm.cycle();
    }
    EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
    EXPECT_LE(arm.worst_ratio, config.governor.velocity_fraction);
    EXPECT_LE(arm.worst_tcp_speed, config.governor.tcp_speed_m_per_s);
    EXPECT_GT(arm.wrapper.diagnostics().governor_hits, 0U) << "the step never needed the governor";
    RecordProperty(GetParam() + (angle == 0.0 ? "_translation" : "_rotation"),
                   "speed ratio " + std::to_string(arm.worst_ratio) + ", TCP " +
                       std::to_string(arm.worst_tcp_speed) + " m/s");
  }
}

// Findings 1 (stop) and 2: with the governor off, the same step overspeeds into a FAULT; the
// controlled stop brings the arm to rest, the hardware's hold is asked for, and a reset holds the
// pose the arm stopped at rather than the target that caused the fault.
TEST_P(StopMeansStop, AFaultFromFullSpeedEndsAtRestAndAResetHoldsThere) {
  pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  config.governor.enabled = false;
  config.validation.max_wn_period = 0.0;  // the stop is what is tested, at any gain
  Arm<> arm(config);
  ASSERT_TRUE(arm.wrapper.submit(stiffStep(arm, Eigen::Vector3d(0.1, 0.0, 0.0), 0.0)).accepted);
  int cycle = 0;
  for (; cycle < 3000 && !arm.faulted(); ++cycle) {
    arm.cycle();
  }
  ASSERT_TRUE(arm.faulted()) << "the step no longer overspeeds: the test tests nothing";
  const Eigen::Vector3d at_fault = arm.tcp();
  const double fault_speed = arm.fastestJoint();
  int stop_cycles = 0;
  for (; stop_cycles < 2000 && arm.fastestJoint() >= pipeline::SafeHold::kRestSpeed;
       ++stop_cycles) {
    arm.cycle();
  }
  const double stop_distance_m = (arm.tcp() - at_fault).norm();
  for (int rest = 0; rest < 200; ++rest) {
    arm.cycle();
  }
  EXPECT_LT(stop_cycles, 2000) << "not at rest 2 s after the FAULT";
  EXPECT_TRUE(arm.held) << "the hardware's hold was never asked for";
  EXPECT_LT((arm.tcp() - at_fault).norm(), 0.15);
  RecordProperty(GetParam() + "_stop", "from " + std::to_string(fault_speed) +
                                           " rad/s: " + std::to_string(stop_cycles) + " ms, " +
                                           std::to_string(stop_distance_m * 100.0) + " cm");

  const Eigen::Vector3d at_reset = arm.tcp();
  arm.worst_ratio = 0.0;
  arm.wrapper.reset();
  for (int after = 0; after < 1000; ++after) {
    arm.cycle();
  }
  EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
  EXPECT_LT((arm.tcp() - at_reset).norm(), 0.005) << "the reset re-armed a target";
  EXPECT_LT(arm.worst_ratio, 0.05);
}

// Finding 6: the governor bounds every law and output mode. A Cartesian law on drives with an
// onboard PD (joint_pd), and a joint law, each with gains past what the gain bound would accept
// (off here: the governor is what is tested): a 10 cm and a 0.5 rad step stay below the governed
// speed.
TEST_P(StopMeansStop, JointPdDrivesAndJointLawsAreGovernedToo) {
  pipeline::WrapperConfig cartesian = simCartesianConfig(GetParam());
  cartesian.output.mode = OutputMode::kJointPd;
  cartesian.validation.max_wn_period = 0.0;
  {
    Arm<> arm(cartesian);
    CartesianCommand step = stiffStep(arm, Eigen::Vector3d(0.1, 0.0, 0.0), 0.0);
    step.stiffness_translational *= 10.0;
    ASSERT_TRUE(arm.wrapper.submit(step).accepted);
    for (int cycle = 0; cycle < 3000; ++cycle) {
      arm.cycle();
    }
    EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
    EXPECT_LE(arm.worst_ratio, cartesian.governor.velocity_fraction) << "joint_pd";
  }
  pipeline::WrapperConfig joint = host::simControllerConfig(
      GetParam(), "", (kSourceDir / "config" / "sim" / "joint_impedance.yaml").string());
  joint.validation.max_wn_period = 0.0;
  Arm<JointCommand> arm(joint);
  JointCommand step = JointCommand::zero(arm.wrapper.dof());
  step.stamp_s = 1.0;
  step.fields = CommandField::kPosition | CommandField::kStiffness;
  step.position = arm.state.position;
  step.position.array() += 0.45;  // within the 0.5 rad jump limit, every joint at once
  step.stiffness = JointVector::Constant(arm.wrapper.dof(), 5000.0);
  ASSERT_TRUE(arm.wrapper.submit(step).accepted);
  for (int cycle = 0; cycle < 3000; ++cycle) {
    arm.cycle();
  }
  EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
  EXPECT_LE(arm.worst_ratio, joint.governor.velocity_fraction) << "joint law";
  RecordProperty(GetParam() + "_joint_law", "speed ratio " + std::to_string(arm.worst_ratio));
}

INSTANTIATE_TEST_SUITE_P(Robots, StopMeansStop, ::testing::ValuesIn(model::availableRobots()),
                         [](const auto& test) { return test.param; });

}  // namespace
}  // namespace comply::testing
