// The intake queue between senders and the cycle: commands sent between two cycles are all
// applied, in order, by the next one; a sender faster than the cycle is refused with queue_full
// once the queue holds its capacity, instead of overwriting accepted commands; and the fault and
// rejection texts, written by two threads, never tear or block a reader.

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

class JointIntake : public ::testing::Test {
 protected:
  JointIntake() : wrapper(fr3Config(kJointImpedancePlugin)) {}
  void SetUp() override {
    state = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(state);
  }
  JointCommand stiffness(double stamp_s, double value) const {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kStiffness;
    command.stiffness.setConstant(value);
    return command;
  }

  JointWrapper wrapper;
  JointState state;
  TorqueBuffer torque;
};

TEST_F(JointIntake, EveryCommandBetweenTwoCyclesIsAppliedInOrder) {
  JointCommand damping = JointCommand::zero(kFr3Dof);
  damping.stamp_s = 1.0;
  damping.fields = CommandField::kDamping;
  damping.damping.setConstant(7.0);
  ASSERT_TRUE(wrapper.submit(damping).accepted);
  ASSERT_TRUE(wrapper.submit(stiffness(2.0, 150.0)).accepted);
  ASSERT_TRUE(wrapper.submit(stiffness(3.0, 160.0)).accepted);
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  const JointCommand in_force = wrapper.lastAccepted();
  EXPECT_EQ(in_force.damping, JointVector(JointVector::Constant(kFr3Dof, 7.0)));
  EXPECT_EQ(in_force.stiffness, JointVector(JointVector::Constant(kFr3Dof, 160.0)));
  EXPECT_EQ(in_force.stamp_s, 3.0);
}

TEST_F(JointIntake, ASenderFasterThanTheCycleIsRefusedWithQueueFull) {
  const auto capacity = static_cast<int>(Controller::kIntakeCapacity);
  for (int i = 0; i < capacity; ++i) {
    ASSERT_TRUE(wrapper.submit(stiffness(1.0 + i, 100.0 + i)).accepted) << i;
  }
  const Verdict refused = wrapper.submit(stiffness(1000.0, 999.0));
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.reason, RejectionReason::kQueueFull);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.rejections[static_cast<std::size_t>(RejectionReason::kQueueFull)], 1U);
  EXPECT_EQ(diagnostics.commands_accepted, static_cast<std::uint64_t>(capacity));

  // The cycle applies the accepted ones (the last accepted is in force, not the refused one) and
  // the queue takes commands again.
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_EQ(wrapper.lastAccepted().stiffness[0], 100.0 + capacity - 1);
  // The refused command's stamp was not taken: an older stamp than it is still accepted.
  EXPECT_TRUE(wrapper.submit(stiffness(capacity + 1.0, 321.0)).accepted);
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_EQ(wrapper.lastAccepted().stiffness[0], 321.0);
}

TEST(Diagnostics, FaultAndRejectionWritersNeverBlockAReader) {
  // Two writers on one text used to leave its sequence counter odd and a reader spinning.
  Diagnostics diagnostics;
  std::atomic<bool> stop{false};
  std::thread cycle([&] {
    while (!stop.load()) {
      diagnostics.setFault("plugin: ", "step failed");
    }
  });
  std::thread sender([&] {
    while (!stop.load()) {
      diagnostics.setRejection("command rejected: ", "pose_jump: too far");
    }
  });
  for (int i = 0; i < 20'000; ++i) {
    const DiagnosticsSnapshot snapshot = diagnostics.snapshot();
    ASSERT_TRUE(snapshot.last_fault.empty() || snapshot.last_fault == "plugin: step failed");
    ASSERT_TRUE(snapshot.last_rejection.empty() ||
                snapshot.last_rejection == "command rejected: pose_jump: too far");
  }
  stop.store(true);
  cycle.join();
  sender.join();
  const DiagnosticsSnapshot last = diagnostics.snapshot();
  EXPECT_EQ(last.last_fault, "plugin: step failed");
  EXPECT_EQ(last.last_rejection, "command rejected: pose_jump: too far");
  EXPECT_TRUE(last.last_error == last.last_fault || last.last_error == last.last_rejection);
}

}  // namespace
}  // namespace comply::pipeline::test
