// The cycle's own stage objects alone (frozen_state.hpp, command_watchdog.hpp, safe_hold.hpp):
// each keeps its state between cycles and forgets it in reset(), which activation calls for
// every stage (Controller::resetStages). Their effect inside a running cycle is covered by the
// wrapper tests (wrapper_frozen_state_test, wrapper_watchdog_test, wrapper_fault_test).

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "comply/pipeline/command_watchdog.hpp"
#include "comply/pipeline/frozen_state.hpp"
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

TEST(SafeHold, HoldsTheLastUsableGravityAndDampsUnlessTheStreamIsFrozen) {
  const WrapperConfig config = fr3Config(kJointImpedancePlugin);
  Controller controller(resolveController(config));
  const CycleParameters& parameters = controller.resolved().parameters;
  const JointState state = restingAt(controller, fr3Home());
  controller.activate(state);  // the model data now hold the gravity at home
  SafeHold hold(parameters, kFr3Dof);
  hold.keepGravity(controller.modelData());
  JointState moving = state;
  moving.velocity.setConstant(0.2);
  JointVector torque = JointVector::Zero(kFr3Dof);
  hold.torque(moving, /*frozen=*/false, torque);
  const JointVector gravity = controller.modelData().gravity.head(kFr3Dof);
  for (int i = 0; i < kFr3Dof; ++i) {
    EXPECT_DOUBLE_EQ(torque[i], gravity[i] - parameters.fault_damping[i] * 0.2) << i;
  }
  hold.torque(moving, /*frozen=*/true, torque);
  EXPECT_EQ(torque, gravity) << "a frozen stream's velocity damps nothing";
  moving.velocity.setConstant(std::numeric_limits<double>::infinity());
  hold.torque(moving, /*frozen=*/false, torque);
  EXPECT_EQ(torque, gravity) << "a velocity whose damping overflows damps nothing";
}

}  // namespace
}  // namespace comply::pipeline
