// The cycle's own stage objects alone (frozen_state.hpp, command_watchdog.hpp, safe_hold.hpp,
// motion_governor.hpp): each keeps its state between cycles and forgets it in reset(), which
// activation calls for every stage (Controller::resetStages). Their effect inside a running cycle
// is covered by the wrapper tests (wrapper_frozen_state_test, wrapper_watchdog_test,
// wrapper_fault_test).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "comply/pipeline/command_watchdog.hpp"
#include "comply/pipeline/frozen_state.hpp"
#include "comply/pipeline/motion_governor.hpp"
#include "comply/pipeline/safe_hold.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline {
namespace {

using namespace test;

constexpr double kTimeoutS = 0.05;

JointState stateOf(double position, double velocity) {
  JointState state = JointState::zero(3);
  state.position.setConstant(position);
  state.velocity.setConstant(velocity);
  return state;
}

TEST(FrozenStateDetector, ARepeatedStateIsStaleOnceTheTorqueMovedForTheTimeout) {
  FrozenStateDetector detector(kTimeoutS);
  const JointState state = stateOf(0.3, 0.0);
  JointVector torque = JointVector::Zero(3);
  double t = 0.0;
  // The torque steps by 2 N m while the state repeats bit for bit: stale after the timeout.
  EXPECT_FALSE(detector.check(state, state, torque, t));
  torque.setConstant(2.0);
  for (t = 0.001; t < kTimeoutS - 1e-9; t += 0.001) {
    EXPECT_FALSE(detector.check(state, state, torque, t)) << t;
  }
  EXPECT_TRUE(detector.check(state, state, torque, kTimeoutS + 0.001));
  EXPECT_TRUE(detector.frozen());
  detector.reset();
  EXPECT_FALSE(detector.frozen());
  EXPECT_FALSE(detector.check(state, state, torque, 1.0)) << "reset: the repeat counts afresh";
}

TEST(FrozenStateDetector, AnArmAtRestWithASteadyTorqueIsNotStale) {
  FrozenStateDetector detector(kTimeoutS);
  const JointState state = stateOf(0.3, 0.0);
  const JointVector torque = JointVector::Constant(3, 5.0);
  for (double t = 0.0; t < 10 * kTimeoutS; t += 0.001) {
    EXPECT_FALSE(detector.check(state, state, torque, t));
  }
}

TEST(FrozenStateDetector, ARepeatedVelocityThatShouldHaveMovedTheArmIsStale) {
  FrozenStateDetector detector(kTimeoutS);
  const JointState state = stateOf(0.3, 0.1);  // 0.1 rad/s for 50 ms: 5 mrad, far above 0.1 mrad
  const JointVector torque = JointVector::Constant(3, 5.0);
  bool stale = false;
  for (double t = 0.0; t <= 2 * kTimeoutS && !stale; t += 0.001) {
    stale = detector.check(state, state, torque, t);
  }
  EXPECT_TRUE(stale);
}

TEST(FrozenStateDetector, TheDriversCounterDecidesWhenThereIsOne) {
  FrozenStateDetector detector(kTimeoutS);
  JointState state = stateOf(0.3, 0.0);
  state.sequence_valid = true;
  const JointVector torque = JointVector::Zero(3);
  double t = 0.0;
  for (std::uint64_t sample = 1; sample < 100; ++sample, t += 0.001) {
    state.sequence = sample;
    EXPECT_FALSE(detector.check(state, state, torque, t)) << "a new sample is fresh";
  }
  EXPECT_FALSE(detector.check(state, state, torque, t + kTimeoutS / 2));
  EXPECT_TRUE(detector.check(state, state, torque, t + kTimeoutS)) << "the counter stood still";
  state.sequence += 1;
  EXPECT_FALSE(detector.check(state, state, torque, t + 2 * kTimeoutS));
}

TEST(FrozenStateDetector, ATimeoutOfZeroIsOff) {
  FrozenStateDetector detector(0.0);
  const JointState state = stateOf(0.3, 1.0);
  JointVector torque = JointVector::Zero(3);
  for (double t = 0.0; t < 1.0; t += 0.01) {
    torque.setConstant(t * 100.0);
    EXPECT_FALSE(detector.check(state, state, torque, t));
  }
}

TEST(CommandWatchdog, ExpiresOnceAfterTheTimeoutAndRearmsOnACommand) {
  CommandWatchdog watchdog(0.5);
  watchdog.reset();
  EXPECT_FALSE(watchdog.expires(0.499));
  EXPECT_TRUE(watchdog.expires(0.5));
  EXPECT_FALSE(watchdog.expires(0.6)) << "once";
  watchdog.heard(1.0);
  EXPECT_FALSE(watchdog.expires(1.4));
  EXPECT_TRUE(watchdog.expires(1.5));
  watchdog.reset();
  EXPECT_TRUE(watchdog.expires(0.5)) << "reset: the silence counts from 0 again";
  CommandWatchdog off(0.0);
  EXPECT_FALSE(off.expires(1e9));
}

TEST(SafeHold, StopsEveryJointWithinItsEffortLimitThenHoldsWhereItCameToRest) {
  const WrapperConfig config = fr3Config(kJointImpedancePlugin);
  Controller controller(resolveController(config));
  const CycleParameters& parameters = controller.resolved().parameters;
  const JointState state = restingAt(controller, fr3Home());
  controller.activate(state);  // the model data now hold the gravity at home
  SafeHold hold(parameters, kFr3Dof);
  hold.keepGravity(controller.modelData());
  const JointVector gravity = controller.modelData().gravity.head(kFr3Dof);
  constexpr double kPeriodS = 0.001;

  // Stopping: damping max(fault_damping, m / 2T), at most what the effort limit leaves beside
  // gravity.
  JointState moving = state;
  moving.velocity.setConstant(0.2);
  JointVector torque = JointVector::Zero(kFr3Dof);
  hold.torque(moving, /*frozen=*/false, kPeriodS, torque);
  EXPECT_FALSE(hold.atRest());
  for (int i = 0; i < kFr3Dof; ++i) {
    const double gain =
        std::max(parameters.fault_damping[i], parameters.joint_inertia[i] / (2.0 * kPeriodS));
    const double available = parameters.effort_limit[i] - std::abs(gravity[i]);
    EXPECT_DOUBLE_EQ(torque[i], gravity[i] - std::min(gain * 0.2, available)) << i;
    EXPECT_GT(gain, 5.0 * parameters.fault_damping[i]) << "a stop, not the old light damping";
  }
  moving.velocity.setConstant(50.0);  // far past every limit: each joint brakes with all it has
  hold.torque(moving, false, kPeriodS, torque);
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_NEAR(torque[i], gravity[i] - (parameters.effort_limit[i] - std::abs(gravity[i])), 1e-9)
        << i;
  }

  // At rest: held where it stopped, a spring back to that pose.
  JointState resting = state;
  resting.velocity.setConstant(0.5 * SafeHold::kRestSpeed);
  hold.torque(resting, false, kPeriodS, torque);
  EXPECT_TRUE(hold.atRest());
  JointState pushed = resting;
  pushed.velocity.setZero();
  pushed.position.array() += 0.01;
  hold.torque(pushed, false, kPeriodS, torque);
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_LT(torque[i], gravity[i]) << i << ": pushed off the rest pose, pulled back";
  }
  hold.reset();
  EXPECT_FALSE(hold.atRest());

  hold.torque(moving, /*frozen=*/true, kPeriodS, torque);
  EXPECT_EQ(torque, gravity) << "a frozen stream's velocity damps nothing";
  moving.velocity.setConstant(std::numeric_limits<double>::infinity());
  hold.torque(moving, /*frozen=*/false, kPeriodS, torque);
  EXPECT_EQ(torque, gravity) << "a velocity whose damping overflows damps nothing";
}

TEST(MotionGovernor, LeavesSlowJointsAloneAndScalesThePushOfFastOnes) {
  WrapperConfig config = fr3Config(kCartesianImpedancePlugin);
  Controller controller(resolveController(config));
  const CycleParameters& parameters = controller.resolved().parameters;
  const JointState state = restingAt(controller, fr3Home());
  controller.activate(state);
  const MotionGovernor governor(controller.resolved(), /*tcp=*/false);
  ASSERT_TRUE(governor.enabled());
  const JointVector& governed = governor.governedSpeed();
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_DOUBLE_EQ(governed[i], 0.8 * parameters.velocity_limit[i]);
  }
  constexpr double kPeriodS = 0.001;
  const Vector6d kNoTwist = Vector6d::Zero();  // the TCP is not governed here
  const JointVector compensation = JointVector::Constant(kFr3Dof, 3.0);

  // Slow (below 0.2 w): the law's torque passes bit for bit, however large (a contact push).
  JointState slow = state;
  slow.velocity = 0.1 * governed;
  JointVector law = JointVector::Constant(kFr3Dof, 80.0);
  JointVector torque = compensation + law;
  GovernorResult result =
      governor.apply(slow, kNoTwist, controller.modelData(), kPeriodS, law, torque);
  EXPECT_FALSE(result.acted());
  EXPECT_EQ(torque, compensation + JointVector::Constant(kFr3Dof, 80.0));

  // Fast, pushed along the motion: scaled, direction kept, the compensation untouched.
  JointState fast = state;
  fast.velocity = 0.6 * governed;
  law = JointVector::Constant(kFr3Dof, 10.0);
  torque = compensation + law;
  result = governor.apply(fast, kNoTwist, controller.modelData(), kPeriodS, law, torque);
  ASSERT_LT(result.share, 1.0);
  EXPECT_GT(result.share, 0.0);
  EXPECT_FALSE(result.braked);
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_DOUBLE_EQ(law[i], 10.0 * result.share) << i;
    EXPECT_DOUBLE_EQ(torque[i], compensation[i] + law[i]) << i;
  }

  // The law braking a fast joint alone is never scaled.
  JointState one_fast = state;
  one_fast.velocity[3] = 0.6 * governed[3];
  law = JointVector::Zero(kFr3Dof);
  law[3] = -20.0;
  torque = compensation + law;
  result = governor.apply(one_fast, kNoTwist, controller.modelData(), kPeriodS, law, torque);
  EXPECT_FALSE(result.acted());
  EXPECT_EQ(law[3], -20.0);

  // Past 0.85 w: no push at all, and a brake against the motion.
  JointState over = state;
  over.velocity = 0.95 * governed;
  law = JointVector::Constant(kFr3Dof, 5.0);
  torque = compensation + law;
  result = governor.apply(over, kNoTwist, controller.modelData(), kPeriodS, law, torque);
  EXPECT_EQ(result.share, 0.0);
  EXPECT_TRUE(result.braked);
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_LT(torque[i], compensation[i]) << i << ": braked against its motion";
    EXPECT_GE(torque[i], compensation[i] - parameters.effort_limit[i]) << i;
  }
}

TEST(MotionGovernor, BrakesATcpPastItsSpeed) {
  WrapperConfig config = fr3Config(kCartesianImpedancePlugin);
  Controller controller(resolveController(config));
  const JointState state = restingAt(controller, fr3Home());
  controller.activate(state);
  const MotionGovernor governor(controller.resolved(), /*tcp=*/true);
  const model::Data& data = controller.modelData();
  // A joint velocity that moves the TCP at 1.5 m/s along base x, slow on every joint's scale.
  const Eigen::Matrix<double, 3, Eigen::Dynamic> linear = data.jacobian.topRows(3);
  JointState fast = state;
  fast.velocity = linear.transpose() *
                  (linear * linear.transpose()).ldlt().solve(Eigen::Vector3d(1.5, 0.0, 0.0));
  JointVector law = JointVector::Zero(kFr3Dof);
  JointVector torque = JointVector::Zero(kFr3Dof);
  const Vector6d twist = data.jacobian * fast.velocity;
  const GovernorResult result = governor.apply(fast, twist, data, 0.001, law, torque);
  ASSERT_TRUE(result.braked);
  const Eigen::Vector3d force =
      (linear * linear.transpose()).ldlt().solve(linear * torque.head(kFr3Dof));  // J^T F = torque
  EXPECT_LT(force.x(), 0.0) << "braked against the TCP's motion";
  EXPECT_LT(fast.velocity.dot(torque), 0.0) << "the brake takes energy out";
}

}  // namespace
}  // namespace comply::pipeline
