// The stability guard's three conditions one at a time, on the FR3 with synthetic states: a joint
// over its URDF speed limit for longer than velocity_time_s (one noisy sample is not enough), a
// joint past its URDF position limit by more than the margin, a joint held at its effort limit for
// longer than saturation_time_s. Each ends in FAULT naming the joint; off, none does.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr int kJoint = 3;  // fr3_joint4: 2.62 rad/s in the URDF

class Guard : public ::testing::Test {
 protected:
  void start(const std::string& lines = {}) {
    wrapper_ = std::make_unique<JointWrapper>(fr3Config(kJointImpedancePlugin, lines));
    state_ = restingAt(wrapper_->controller(), fr3Home());
    wrapper_->activate(state_);
  }
  CycleStatus cycle() { return wrapper_->update(state_, kPeriod, torque_.span()); }
  [[nodiscard]] double speedLimit() const {
    return wrapper_->controller().model().limits(kJoint).velocity;
  }
  std::unique_ptr<JointWrapper> wrapper_;
  JointState state_;
  TorqueBuffer torque_;
};

TEST_F(Guard, AJointOverItsSpeedLimitForFiveMillisecondsIsAFault) {
  start();
  state_.velocity[kJoint] = 1.1 * speedLimit();
  EXPECT_EQ(cycle(), CycleStatus::kOk) << "one sample over the limit is not a runaway";
  state_.velocity[kJoint] = 0.0;
  EXPECT_EQ(cycle(), CycleStatus::kOk);
  state_.velocity[kJoint] = -1.1 * speedLimit();
  int cycles = 0;
  while (cycle() == CycleStatus::kOk && cycles < 100) {
    ++cycles;
  }
  EXPECT_EQ(cycles, 5) << "velocity_time_s is 5 ms at 1 kHz";
  const std::string fault = wrapper_->diagnostics().last_fault;
  EXPECT_NE(fault.find("stability guard: fr3_joint4 at 2.88 rad/s, over 2.62 rad/s"),
            std::string::npos)
      << fault;
}

TEST_F(Guard, AJointPastItsLimitByMoreThanTheMarginIsAFault) {
  start();
  const double upper = wrapper_->controller().model().limits(kJoint).upper;
  state_.position[kJoint] = upper + 0.04;
  EXPECT_EQ(cycle(), CycleStatus::kOk) << "within the 0.05 rad margin";
  state_.position[kJoint] = upper + 0.06;
  EXPECT_EQ(cycle(), CycleStatus::kFault);
  EXPECT_NE(wrapper_->diagnostics().last_fault.find("fr3_joint4 at"), std::string::npos);
  EXPECT_NE(wrapper_->diagnostics().last_fault.find("past its URDF limit"), std::string::npos);
}

TEST_F(Guard, AJointHeldAtItsEffortLimitTooLongIsAFault) {
  // A state that repeats while the torque moves would be a frozen sensor: that check is off here.
  start(
      "torque_rate_limit_nm_per_s: 1.0e9\nfrozen_state_timeout_s: 0\n"
      "stability_guard:\n  saturation_time_s: 0.2\n");
  JointCommand push = JointCommand::zero(kFr3Dof);
  push.stamp_s = 1.0;
  push.fields = CommandField::kTorqueFeedforward;
  push.torque_feedforward[0] = 500.0;
  ASSERT_TRUE(wrapper_->submit(push).accepted);
  int cycles = 0;
  while (cycle() == CycleStatus::kOk && cycles < 1000) {
    ++cycles;
  }
  EXPECT_EQ(cycles, 199) << "the 200th cycle at the limit (0.2 s) is the FAULT";
  EXPECT_NE(wrapper_->diagnostics().last_fault.find("fr3_joint1 at its effort limit of 87 N m"),
            std::string::npos)
      << wrapper_->diagnostics().last_fault;
}

TEST_F(Guard, OffNothingIsAFault) {
  start("stability_guard:\n  enabled: false\n");
  state_.velocity[kJoint] = 10.0 * speedLimit();
  state_.position[kJoint] = wrapper_->controller().model().limits(kJoint).upper + 1.0;
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(cycle(), CycleStatus::kOk);
  }
}

}  // namespace
}  // namespace comply::pipeline::test
