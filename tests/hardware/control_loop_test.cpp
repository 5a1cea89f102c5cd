// The loop's contract with the hardware: a cycle whose controller writes a torque reaches
// write(); a cycle without output (an inactive controller) asks the hardware to hold the arm
// instead of leaving the last torque on the motors. A cycle that starts late misses its deadline
// even when its computing is short.

#include "comply/hardware/control_loop.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "comply/hardware/loop_clock.hpp"
#include "stalling_observer.hpp"

namespace comply::hardware {
namespace {

/// Counts what the loop asked of it.
class RecordingHardware final : public HardwareInterface {
 public:
  explicit RecordingHardware(bool can_hold) : can_hold_(can_hold) {}
  [[nodiscard]] int dof() const noexcept override { return 2; }
  bool read(JointState& state) noexcept override {
    state = JointState::zero(2);
    return true;
  }
  bool write(std::span<const double> /*torque*/) noexcept override {
    ++writes;
    return true;
  }
  bool hold() noexcept override {
    ++holds;
    return can_hold_;
  }
  int writes = 0;
  int holds = 0;

 private:
  bool can_hold_;
};

/// Writes a torque in the cycles it is told to, nothing in the others (as an inactive wrapper);
/// asks for the hardware's hold when told to (as a wrapper in FAULT on a frozen sensor).
class SwitchedController final : public CycleController {
 public:
  [[nodiscard]] int dof() const noexcept override { return 2; }
  bool cycle(const JointState& state, double /*period_s*/,
             ActuatorCommand& command) noexcept override {
    command.effort[0] = command.effort[1] = 1.0;
    command.position[0] = command.position[1] = 0.5;
    saw_wrench = state.wrench_valid ? state.wrench[2] : 0.0;
    saw_sequence = state.sequence_valid ? state.sequence : 0;
    return active;
  }
  [[nodiscard]] OutputMode outputMode() const noexcept override { return mode; }
  [[nodiscard]] bool wantsHold() const noexcept override { return wants_hold; }
  void warm(const JointState& /*last_state*/) noexcept override {
    ++warms;
    warmed_at_s = monotonicSeconds();
  }
  OutputMode mode = OutputMode::kTorque;
  double saw_wrench = 0.0;
  std::uint64_t saw_sequence = 0;
  bool active = false;
  bool wants_hold = false;
  int warms = 0;
  double warmed_at_s = 0.0;
};

TEST(ControlLoop, ACycleWithoutOutputHoldsTheArmInsteadOfLeavingTheLastTorque) {
  RecordingHardware hardware(true);
  SwitchedController controller;
  FreeRunningClock clock;
  ControlLoop loop(hardware, controller, clock, {.period_s = 0.001});
  for (int cycle = 0; cycle < 5; ++cycle) {
    ASSERT_TRUE(loop.runOnce());
  }
  EXPECT_EQ(hardware.holds, 5);
  EXPECT_EQ(hardware.writes, 0);
  controller.active = true;
  for (int cycle = 0; cycle < 3; ++cycle) {
    ASSERT_TRUE(loop.runOnce());
  }
  EXPECT_EQ(hardware.writes, 3);
  EXPECT_EQ(hardware.holds, 5) << "an active cycle writes; it does not hold";
  EXPECT_EQ(loop.stats().held_cycles, 5U);
}

TEST(ControlLoop, AControllerThatDistrustsItsStateGetsTheHardwaresHoldAfterItsTorque) {
  RecordingHardware hardware(true);
  SwitchedController controller;
  controller.active = true;
  controller.wants_hold = true;
  FreeRunningClock clock;
  ControlLoop loop(hardware, controller, clock, {.period_s = 0.001});
  ASSERT_TRUE(loop.runOnce());
  EXPECT_EQ(hardware.writes, 1) << "the holding torque is still written";
  EXPECT_EQ(hardware.holds, 1) << "and the brakes asked for on top";
  EXPECT_EQ(loop.stats().held_cycles, 1U);
}

TEST(ControlLoop, HardwareWithoutAHoldModeIsNotCountedAsHeld) {
  RecordingHardware hardware(false);
  SwitchedController controller;
  FreeRunningClock clock;
  ControlLoop loop(hardware, controller, clock, {.period_s = 0.001});
  ASSERT_TRUE(loop.runOnce());
  EXPECT_EQ(hardware.holds, 1) << "asked";
  EXPECT_EQ(loop.stats().held_cycles, 0U) << "but it could not hold";
}

/// Records when each cycle read the hardware.
class TimedHardware final : public HardwareInterface {
 public:
  [[nodiscard]] int dof() const noexcept override { return 2; }
  bool read(JointState& state) noexcept override {
    read_at_s = monotonicSeconds();
    state = JointState::zero(2);
    return true;
  }
  bool write(std::span<const double> /*torque*/) noexcept override { return true; }
  double read_at_s = 0.0;
};

TEST(ControlLoop, WarmAheadWarmsTheControllerBeforeEachCycleOnAWallClockOnly) {
  constexpr double kAheadS = 200e-6;
  TimedHardware hardware;
  SwitchedController controller;
  controller.active = true;
  WallClock wall;
  ControlLoop loop(hardware, controller, wall, {.period_s = 0.002, .warm_ahead_s = kAheadS});
  double smallest_lead_s = 1.0;
  for (int cycle = 0; cycle < 20; ++cycle) {
    ASSERT_TRUE(loop.runOnce());
    if (cycle > 0) {
      smallest_lead_s = std::min(smallest_lead_s, hardware.read_at_s - controller.warmed_at_s);
    }
  }
  EXPECT_EQ(controller.warms, 19) << "before every cycle but the first";
  // Warmed first, then the cycle read the hardware at its start, after spinning there.
  EXPECT_GT(smallest_lead_s, 0.0);

  SwitchedController simulated;
  FreeRunningClock free_running;  // its time does not pass by itself: no spinning on it
  ControlLoop replay(hardware, simulated, free_running,
                     {.period_s = 0.001, .warm_ahead_s = kAheadS});
  for (int cycle = 0; cycle < 5; ++cycle) {
    ASSERT_TRUE(replay.runOnce());
  }
  EXPECT_EQ(simulated.warms, 0);
}

TEST(ControlLoop, ACycleThatStartsLateAfterAStallIsAnOverrun) {
  RecordingHardware hardware(true);
  SwitchedController controller;
  controller.active = true;
  WallClock wall;
  ControlLoop loop(hardware, controller, wall, {.period_s = 0.001, .cycles = 30});
  testing::StallingObserver observer(10);
  loop.setObserver(&observer);
  const LoopStats stats = loop.run();
  ASSERT_EQ(observer.lateness_s.size(), 30U);
  // Cycle 11 was due 1 ms after cycle 10 started and began 15 ms or more after that (a sleep
  // never returns early): 14 ms late, past its own deadline before it computed anything.
  EXPECT_GE(observer.lateness_s[11], 0.014);
  EXPECT_TRUE(observer.overrun[11]) << "a cycle that starts after its deadline overran it";
  EXPECT_GE(stats.overruns, 1U);
  EXPECT_GE(stats.max_start_lateness_s, 0.014);
  EXPECT_EQ(stats.max_start_lateness_s,
            *std::max_element(observer.lateness_s.begin(), observer.lateness_s.end()));
}

/// Position drives with a wrist force/torque sensor: takes position commands only.
class PositionArm final : public HardwareInterface {
 public:
  [[nodiscard]] int dof() const noexcept override { return 2; }
  bool read(JointState& state) noexcept override {
    state = JointState::zero(2);
    return true;
  }
  bool write(std::span<const double> /*torque*/) noexcept override { return false; }
  [[nodiscard]] bool accepts(OutputMode mode) const noexcept override {
    return mode == OutputMode::kPosition;
  }
  bool writeCommand(const ActuatorCommand& command) noexcept override {
    written_position = command.position[0];
    return command.mode == OutputMode::kPosition;
  }
  bool readWrench(Vector6d& wrench) noexcept override {
    wrench = Vector6d::Zero();
    wrench[2] = -7.5;
    return true;
  }
  bool readSequence(std::uint64_t& sequence) noexcept override {
    sequence = ++samples;
    return true;
  }
  double written_position = 0.0;
  std::uint64_t samples = 40;
};

TEST(ControlLoop, RefusesAControllerWhoseOutputModeTheDrivesDoNotTake) {
  PositionArm position_arm;
  SwitchedController torque_controller;
  FreeRunningClock clock;
  try {
    ControlLoop loop(position_arm, torque_controller, clock, {.period_s = 0.001});
    FAIL() << "a torque controller on position drives was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "control loop: the controller's output.mode is torque but the hardware's drives "
                 "take only position; set output.mode to one of them");
  }
  RecordingHardware torque_arm(true);
  SwitchedController joint_pd;
  joint_pd.mode = OutputMode::kJointPd;
  EXPECT_THROW(ControlLoop(torque_arm, joint_pd, clock, {.period_s = 0.001}), std::invalid_argument)
      << "the interface's default accepts torque alone";
}

TEST(ControlLoop, WritesTheCommandInTheControllersModeAndPassesTheWrenchReading) {
  PositionArm arm;
  SwitchedController controller;
  controller.mode = OutputMode::kPosition;
  controller.active = true;
  FreeRunningClock clock;
  ControlLoop loop(arm, controller, clock, {.period_s = 0.001});
  ASSERT_TRUE(loop.runOnce());
  EXPECT_EQ(loop.stats().write_failures, 0U);
  EXPECT_EQ(arm.written_position, 0.5);
  EXPECT_EQ(loop.lastCommand().mode, OutputMode::kPosition);
  EXPECT_EQ(controller.saw_wrench, -7.5) << "the sensor's reading reaches the controller";
  EXPECT_EQ(controller.saw_sequence, 41U) << "and so does the driver's sample counter";
}

}  // namespace
}  // namespace comply::hardware
