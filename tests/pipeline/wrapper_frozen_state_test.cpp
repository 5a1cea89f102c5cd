// A frozen sensor stream (docs/design.md, "Safety semantics"): a joint state repeated bit for bit
// for frozen_state_timeout_s while the torque sent moves by more than kFrozenStateTorqueChangeNm
// is stale, and the controller holds in FAULT without damping its stale velocity. A state that
// repeats while the torque repeats too (a simulator at rest) is not.

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kTolerance = 1e-9;

class FrozenState : public ::testing::Test {
 protected:
  explicit FrozenState(const std::string& timeout = "0.1")
      : wrapper(fr3Config(kJointImpedancePlugin,
                          "fault_damping: [1, 2, 3, 4, 5, 6, 7]\n"
                          "frozen_state_timeout_s: " +
                              timeout +
                              "\ntorque_rate_limit_nm_per_s: " + std::to_string(kNoRateLimit))) {}

  void SetUp() override {
    // Moving, so that a hold that damped the stale velocity would show.
    state = restingAt(wrapper.controller(), fr3Home());
    state.velocity.setConstant(0.1);
    wrapper.activate(state);
  }

  /// A 0.2 rad step on joint 1: the torque moves by tens of N m at once.
  void sendStep() {
    JointCommand step = JointCommand::zero(kFr3Dof);
    step.stamp_s = 1.0;
    step.fields = CommandField::kPosition;
    step.position = offset(fr3Home(), 0, 0.2);
    ASSERT_TRUE(wrapper.submit(step).accepted);
  }

  CycleStatus cycle(const JointState& measured) {
    return wrapper.update(measured, kPeriod, torque.span());
  }

  /// Cycles at the same state until the first FAULT; the number of cycles run (or `limit`).
  int cyclesUntilFault(int limit) {
    for (int i = 1; i <= limit; ++i) {
      if (cycle(state) == CycleStatus::kFault) {
        return i;
      }
    }
    return limit;
  }

  JointWrapper wrapper;
  JointState state;
  TorqueBuffer torque;
};

TEST_F(FrozenState, RepeatedStateWhileTheTorqueMovesFaultsAfterTheTimeout) {
  sendStep();
  const int faulted_at = cyclesUntilFault(1000);
  // 0.1 s at 1 kHz, counted from the first repeat (time steps are summed in floating point).
  EXPECT_GE(faulted_at, 99);
  EXPECT_LE(faulted_at, 102);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.faults, 1U);
  EXPECT_NE(diagnostics.last_error.find("stale sensor stream"), std::string::npos)
      << diagnostics.last_error;
  // Gravity at the state, no damping: the velocity the stream repeats is not the arm's.
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), state.position),
                            kTolerance);
}

TEST_F(FrozenState, ARepeatedNanEffortRepeatsToo) {
  // A robot without torque sensing may send NaN efforts; NaN != NaN must not hide the repeat.
  state.effort.setConstant(std::numeric_limits<double>::quiet_NaN());
  ASSERT_EQ(cycle(state), CycleStatus::kOk);  // the repeat starts from here
  sendStep();
  const int faulted_at = cyclesUntilFault(1000);
  EXPECT_GE(faulted_at, 99);
  EXPECT_LE(faulted_at, 103);
}

TEST_F(FrozenState, ResetNeedsAStateThatMovesAgain) {
  sendStep();
  ASSERT_LT(cyclesUntilFault(1000), 1000);
  wrapper.reset();
  EXPECT_EQ(cycle(state), CycleStatus::kFault) << "a reset on a still-frozen stream";
  JointState fresh = state;
  fresh.position[2] += 1e-6;
  EXPECT_EQ(cycle(fresh), CycleStatus::kFault) << "a fresh state alone does not leave FAULT";
  wrapper.reset();
  EXPECT_EQ(cycle(fresh), CycleStatus::kOk);
}

// A driver with a sample counter (HardwareInterface::readSequence): the counter decides. One that
// stands still is a stale stream even where the samples alone could not tell (an arm at rest
// repeats its state and its torque; pushed, it moves while the stream repeats the old pose).
TEST_F(FrozenState, ADriverCounterThatStandsStillIsStaleWhateverTheSamples) {
  state.velocity.setZero();
  state.sequence_valid = true;
  state.sequence = 1234;
  const int faulted_at = cyclesUntilFault(1000);
  EXPECT_GE(faulted_at, 99);
  EXPECT_LE(faulted_at, 102);
  EXPECT_NE(wrapper.diagnostics().last_error.find("sample counter has not advanced"),
            std::string::npos)
      << wrapper.diagnostics().last_error;
  EXPECT_TRUE(wrapper.controller().holdRequested()) << "the brakes are asked for";
  // The counter moving again makes the state usable: a reset takes.
  wrapper.reset();
  ++state.sequence;
  EXPECT_EQ(cycle(state), CycleStatus::kOk);
}

// ... and one that advances keeps a bit-identical state fresh while the torque moves (an arm
// pressing on a wall: its encoders repeat), where the samples alone would have faulted.
TEST_F(FrozenState, ADriverCounterThatAdvancesKeepsARepeatedStateFresh) {
  state.velocity.setZero();
  state.sequence_valid = true;
  sendStep();
  for (int i = 0; i < 1000; ++i) {
    ++state.sequence;
    ASSERT_EQ(cycle(state), CycleStatus::kOk) << "cycle " << i;
  }
  EXPECT_EQ(wrapper.diagnostics().faults, 0U);
}

TEST_F(FrozenState, RepeatedStateWithASteadyTorqueIsNotAFault) {
  // An arm (or a simulator) at rest repeats its state, and the law its torque: 2 s of it.
  state.velocity.setZero();
  const int cycles = cyclesUntilFault(2000);
  EXPECT_EQ(cycles, 2000);
  EXPECT_EQ(wrapper.diagnostics().faults, 0U);
}

// A stream that repeats a moving sample while the law's torque stays put (an arm pushed by hand
// moved 2.9 rad unnoticed): the velocity it reports would have moved the position, and it did not.
TEST_F(FrozenState, ARepeatedMovingSampleIsStaleEvenWithASteadyTorque) {
  const int faulted_at = cyclesUntilFault(1000);  // 0.1 rad/s on every joint, no command
  EXPECT_GE(faulted_at, 99);
  EXPECT_LE(faulted_at, 102);
  EXPECT_NE(wrapper.diagnostics().last_error.find("its own velocity should have moved it"),
            std::string::npos)
      << wrapper.diagnostics().last_error;
}

TEST_F(FrozenState, ChangingStateIsNeverFrozenWhateverTheTorque) {
  sendStep();
  for (int i = 0; i < 500; ++i) {
    state.position[6] += (i % 2 == 0 ? 1.0 : -1.0) * 1e-9;  // a least-significant flicker
    ASSERT_EQ(cycle(state), CycleStatus::kOk) << "cycle " << i;
  }
}

class FrozenStateCheckOff : public FrozenState {
 protected:
  FrozenStateCheckOff() : FrozenState("0") {}
};

TEST_F(FrozenStateCheckOff, ZeroTimeoutNeverFaults) {
  sendStep();
  EXPECT_EQ(cyclesUntilFault(1000), 1000);
  EXPECT_EQ(wrapper.diagnostics().faults, 0U);
}

}  // namespace
}  // namespace comply::pipeline::test
