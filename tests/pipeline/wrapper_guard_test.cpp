// The stability guard's four conditions one at a time, on the FR3 with synthetic states: a joint
// over its URDF speed limit for longer than velocity_time_s (one noisy sample is not enough), a
// joint past its URDF position limit by more than the margin, a joint held at its effort limit for
// longer than saturation_time_s, an oscillation that gains energy while the command stays. Each
// ends in FAULT naming the joint; off, none does.

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

/// fr3_joint4 swinging at 8 Hz about home, its energy growing e^t from a small start: what a loop
/// that generates energy looks like, well inside the speed limit.
void swing(JointState& state, double t_s) {
  state.velocity[kJoint] = 0.3 * std::exp(0.5 * t_s) * std::sin(2.0 * M_PI * 8.0 * t_s);
}

TEST_F(Guard, AnOscillationThatGainsEnergyUnderASteadyCommandIsAFault) {
  start();
  int cycles = 0;
  while (cycles < 5000) {
    swing(state_, cycles * kPeriod);
    if (cycle() != CycleStatus::kOk) {
      break;
    }
    ++cycles;
  }
  ASSERT_LT(cycles, 5000) << "no FAULT in 5 s";
  // fr3_joint4's lightest inertia is about 0.7 kg m^2 (with its rotor): 0.03 J at the start,
  // 0.05 J after 0.5 s, 4x the run's start (0.25 s windows) after about 1.5 s.
  EXPECT_GT(cycles * kPeriod, 1.0);
  EXPECT_LT(cycles * kPeriod, 2.5);
  EXPECT_LT(std::abs(state_.velocity[kJoint]), speedLimit()) << "the speed rule would have tripped";
  const std::string fault = wrapper_->diagnostics().last_fault;
  EXPECT_NE(fault.find("stability guard: an oscillation of fr3_joint4 gained energy from"),
            std::string::npos)
      << fault;
}

TEST_F(Guard, TheSameSwingCommandedBySwingingTheReferenceIsNoFault) {
  start();
  const JointVector home = fr3Home();
  for (int k = 0; k < 4000; ++k) {  // 4 s: the energy x55; at 4.4 s the speed rule trips
    const double t_s = k * kPeriod;
    swing(state_, t_s);
    JointCommand reference = JointCommand::zero(kFr3Dof);
    reference.stamp_s = 1.0 + t_s;
    reference.fields = CommandField::kPosition;
    reference.position = home;
    // The reference swings with the arm, ever wider: the sender drives the growth.
    reference.position[kJoint] += 0.006 * std::exp(0.5 * t_s) * std::sin(2.0 * M_PI * 8.0 * t_s);
    ASSERT_TRUE(wrapper_->submit(reference).accepted) << "at " << t_s << " s";
    ASSERT_EQ(cycle(), CycleStatus::kOk)
        << "at " << t_s << " s: " << wrapper_->diagnostics().last_fault;
  }
}

TEST_F(Guard, TheEnergyRuleOffLetsTheSwingGrow) {
  start("stability_guard:\n  energy_window_s: 0\n");
  for (int k = 0; k < 3000; ++k) {
    swing(state_, k * kPeriod);
    ASSERT_EQ(cycle(), CycleStatus::kOk) << wrapper_->diagnostics().last_fault;
  }
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
