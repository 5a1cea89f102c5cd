// A robot that compensates gravity itself (Franka, KUKA, UR): the wrapper then adds no arm gravity,
// neither to the law's torque, nor to the FAULT hold, nor to the torque the rate limit starts
// from; a payload it does not know about still is. Each case against the same arm without it.

#include <gtest/gtest.h>

#include <limits>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kTolerance = 1e-9;

JointWrapper wrapperFor(const std::string& plugin, bool hardware_compensates_gravity,
                        const std::string& lines = "torque_rate_limit_nm_per_s: 1.0e9") {
  WrapperConfig config = fr3Config(plugin, lines);
  config.hardware_compensates_gravity = hardware_compensates_gravity;
  return JointWrapper(config);
}

TEST(WrapperHardwareGravity, TheLawsTorqueCarriesNoGravityWhenTheRobotAddsIt) {
  JointWrapper ours = wrapperFor(kJointImpedancePlugin, false);
  JointWrapper robots = wrapperFor(kJointImpedancePlugin, true);
  const JointState rest = restingAt(ours.controller(), fr3Home());
  ours.activate(rest);
  robots.activate(rest);
  TorqueBuffer with_gravity;
  TorqueBuffer without_gravity;
  const JointState moved = restingAt(ours.controller(), offset(fr3Home(), 1, 0.05));
  ASSERT_EQ(ours.update(moved, kPeriod, with_gravity.span()), CycleStatus::kOk);
  ASSERT_EQ(robots.update(moved, kPeriod, without_gravity.span()), CycleStatus::kOk);
  const JointVector gravity = gravityAt(ours.controller(), moved.position);
  ASSERT_GT(gravity.cwiseAbs().maxCoeff(), 1.0) << "the pose must load the joints";
  COMPLY_EXPECT_JOINTS_NEAR(JointVector(with_gravity.values - without_gravity.values), gravity,
                            kTolerance);
}

TEST(WrapperHardwareGravity, TheFaultHoldAddsNoGravityWhenTheRobotAddsIt) {
  for (const bool robot_adds_gravity : {false, true}) {
    SCOPED_TRACE(robot_adds_gravity ? "robot adds gravity" : "comply adds gravity");
    JointWrapper wrapper = wrapperFor(kJointImpedancePlugin, robot_adds_gravity);
    const JointState rest = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(rest);
    TorqueBuffer torque;
    ASSERT_EQ(wrapper.update(rest, kPeriod, torque.span()), CycleStatus::kOk);
    JointState broken = rest;
    broken.position[3] = std::numeric_limits<double>::quiet_NaN();
    ASSERT_EQ(wrapper.update(broken, kPeriod, torque.span()), CycleStatus::kFault);
    // At rest the hold is gravity alone (no velocity to damp), or nothing when the robot holds it.
    const JointVector expected = robot_adds_gravity
                                     ? JointVector(JointVector::Zero(kFr3Dof))
                                     : gravityAt(wrapper.controller(), rest.position);
    COMPLY_EXPECT_JOINTS_NEAR(torque.values, expected, kTolerance);
  }
}

TEST(WrapperHardwareGravity, TheRateLimitStartsFromComplysShareOfTheMeasuredTorque) {
  // 1 N m/s at 1 kHz: the first cycle moves at most 1 mN m from where the limit starts.
  // 1 N m/s is far below what the gains need (the point here): the gain bound's rate part off.
  JointWrapper wrapper =
      wrapperFor(kJointImpedancePlugin, true,
                 "torque_rate_limit_nm_per_s: 1.0\nvalidation: {rate_limit_swing_nm: 0}");
  const JointState rest = restingAt(wrapper.controller(), fr3Home());  // effort = gravity
  wrapper.activate(rest);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(rest, kPeriod, torque.span()), CycleStatus::kOk);
  // The law at its seeded reference asks for nothing, and the robot holds the gravity it
  // measures: comply's torque starts at zero, not at the measured gravity.
  EXPECT_LE(torque.values.cwiseAbs().maxCoeff(), 1e-3 + kTolerance) << torque.values.transpose();
}

}  // namespace
}  // namespace comply::pipeline::test
