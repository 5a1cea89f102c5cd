// The UR backend against the emulated controller: the program is sent and runs, the arm follows
// commands on the controller's cycles with every package answered, and each stop (protective, a
// lost link, a program's watchdog) is said (robotStop(), lastStop()) and recovers once cleared.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <thread>

#include "comply/hardware/backend.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/ur/robot_status.hpp"
#include "ur_emulator_support.hpp"

namespace comply::ur::test {
namespace {

constexpr double kPeriod = 0.002;

/// Sends the first position it reads plus a slow sine on the first joint (position mode), or the
/// sine's derivative (velocity mode).
class SineController final : public hardware::CycleController {
 public:
  explicit SineController(OutputMode mode) : mode_(mode) {}
  [[nodiscard]] int dof() const noexcept override { return 6; }
  [[nodiscard]] OutputMode outputMode() const noexcept override { return mode_; }
  bool cycle(const JointState& state, double period_s, ActuatorCommand& command) noexcept override {
    if (!started_) {
      start_ = state.position;
      started_ = true;
    }
    time_s_ += period_s;
    stops_ += state.robot_stop != nullptr ? 1 : 0;
    command.mode = mode_;
    command.position = start_;
    command.velocity.setZero(6);
    const double phase = 2.0 * M_PI * kFrequencyHz * time_s_;
    command.position[0] += kAmplitudeRad * std::sin(phase);
    command.velocity[0] = kAmplitudeRad * 2.0 * M_PI * kFrequencyHz * std::cos(phase);
    target_ = command.position;
    return true;
  }
  static constexpr double kAmplitudeRad = 0.1;
  static constexpr double kFrequencyHz = 0.5;
  JointVector target_;
  int stops_ = 0;

 private:
  OutputMode mode_;
  JointVector start_;
  bool started_ = false;
  double time_s_ = 0.0;
};

/// A protective stop unlocks 1 s after it (PolyScope: 5 s).
UrEmulatorOptions unlockAfterOneSecond() {
  UrEmulatorOptions options = freePorts();
  options.unlock_delay_s = 1.0;
  return options;
}

class UrBackend : public ::testing::Test {
 protected:
  UrEmulator emulator{unlockAfterOneSecond()};
};

TEST_F(UrBackend, FollowsPositionCommandsAnsweringEveryPackage) {
  UrArm arm(armFor(emulator, OutputMode::kPosition));
  EXPECT_EQ(emulator.stats().programs, 1U);
  EXPECT_EQ(arm.controllerVersion().minor, 23U);
  UrClock clock(arm);
  SineController controller(OutputMode::kPosition);
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = kPeriod, .cycles = 1000});
  const hardware::LoopStats loop_stats = loop.run();
  EXPECT_EQ(loop_stats.read_failures, 0U);
  EXPECT_EQ(loop_stats.write_failures, 0U);
  EXPECT_EQ(controller.stops_, 0);
  // The position servos follow the sine within their lag (20 Hz bandwidth: < 5 mrad at 0.3 rad/s).
  const UrEmulatorState state = emulator.state();
  EXPECT_NEAR(state.position[0], controller.target_[0], 0.01);
  EXPECT_TRUE(state.program_running);
  // Every cycle of the loop answered one package, and every package the controller sent is
  // either applied or counted missed. How many a busy host's scheduling makes late or overtaken
  // is the machine's, not asserted here (the 60 s run in ur_loop_test counts them alone on the
  // machine); most are applied.
  const UrEmulatorStats stats = emulator.stats();
  const UrLinkStats link = arm.stats();
  EXPECT_LE(stats.answered + stats.missed, stats.cycles);
  EXPECT_GT(stats.answered, stats.missed);
  EXPECT_EQ(stats.watchdog_stops, 0U);
  EXPECT_EQ(link.skipped_cycles, 0U);
  EXPECT_GE(link.packages, 1000U);
  EXPECT_EQ(link.connections, 1U);
}

TEST_F(UrBackend, FollowsVelocityCommands) {
  UrArm arm(armFor(emulator, OutputMode::kVelocity));
  UrClock clock(arm);
  SineController controller(OutputMode::kVelocity);
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = kPeriod, .cycles = 1000});
  (void)loop.run();
  EXPECT_EQ(emulator.state().program_mode, OutputMode::kVelocity);
  EXPECT_NEAR(emulator.state().position[0], controller.target_[0], 0.02);
}

TEST_F(UrBackend, DroppedPackagesAreCountedAsSkippedCycles) {
  UrArm arm(armFor(emulator, OutputMode::kPosition));
  UrClock clock(arm);
  SineController controller(OutputMode::kPosition);
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = kPeriod, .cycles = 250});
  (void)loop.run();
  emulator.dropPackages(5);
  hardware::ControlLoop more(arm, controller, clock, {.period_s = kPeriod, .cycles = 250});
  (void)more.run();
  EXPECT_EQ(arm.stats().skipped_cycles, 5U);
  EXPECT_EQ(emulator.stats().dropped, 5U);
}

/// The backend on position drives with a SineController, its loop on a thread until this goes
/// (also when an assertion ends the test early).
struct RunningArm {
  explicit RunningArm(UrEmulator& emulator)
      : arm(armFor(emulator, OutputMode::kPosition)),
        clock(arm),
        controller(OutputMode::kPosition),
        loop(arm, controller, clock, {.period_s = kPeriod}),
        thread([this] { (void)loop.run(); }) {}
  ~RunningArm() { loop.stop(); }  // then the thread joins
  RunningArm(const RunningArm&) = delete;
  RunningArm& operator=(const RunningArm&) = delete;

  UrArm arm;
  UrClock clock;
  SineController controller;
  hardware::ControlLoop loop;
  std::jthread thread;
};

TEST_F(UrBackend, AProtectiveStopIsSaidAndRecoversOnceUnlocked) {
  RunningArm running(emulator);
  UrArm& arm = running.arm;
  ASSERT_TRUE(eventually([&] { return emulator.stats().answered > 50; }, 2.0));
  emulator.protectiveStop();
  ASSERT_TRUE(eventually([&] { return arm.lastStop() != nullptr; }, 1.0));
  EXPECT_NE(std::string(arm.lastStop()).find("protective stop"), std::string::npos)
      << arm.lastStop();
  const JointVector held = emulator.state().position;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_LT((emulator.state().position - held).cwiseAbs().maxCoeff(), 1e-6) << "the arm moved";
  // Too early to unlock, then unlocked: the backend sends the program again.
  EXPECT_NE(emulator.dashboard("unlock protective stop").find("Cannot unlock"), std::string::npos);
  // The unlock delay runs on the controller's clock, which a busy host's scheduling slows: asked
  // again until it is past, as an operator would.
  EXPECT_TRUE(eventually(
      [&] { return emulator.dashboard("unlock protective stop") == "Protective stop releasing"; },
      10.0))
      << "never unlocked";
  EXPECT_TRUE(eventually([&] { return arm.lastStop() == nullptr; }, 3.0));
  EXPECT_EQ(emulator.stats().programs, 2U);
}

TEST_F(UrBackend, ALostLinkIsSaidTheProgramStopsTheArmAndTheLinkComesBack) {
  RunningArm running(emulator);
  UrArm& arm = running.arm;
  ASSERT_TRUE(eventually([&] { return emulator.stats().answered > 50; }, 2.0));
  emulator.closeConnections();
  ASSERT_TRUE(eventually([&] { return arm.lastStop() != nullptr; }, 1.0));
  EXPECT_NE(std::string(arm.lastStop()).find("link to the UR controller is lost"),
            std::string::npos)
      << arm.lastStop();
  // Without answers, the program's watchdog stopped the arm; the backend connects again and
  // sends the program again.
  EXPECT_TRUE(eventually([&] { return arm.lastStop() == nullptr; }, 3.0));
  EXPECT_EQ(emulator.stats().watchdog_stops, 1U);
  EXPECT_EQ(arm.stats().connections, 2U);
  EXPECT_EQ(emulator.stats().programs, 2U);
}

// The controller falls silent with its connections open (a switch dropping packets): after a
// second the backend gives the link up and connects anew, its old answer connection closed so
// that the controller lets the new one write the registers (one writer per input).
TEST_F(UrBackend, ASilentLinkIsGivenUpAndMadeAgainWithItsRegistersFreed) {
  RunningArm running(emulator);
  UrArm& arm = running.arm;
  ASSERT_TRUE(eventually([&] { return emulator.stats().answered > 50; }, 2.0));
  emulator.dropPackages(750);  // 1.5 s
  ASSERT_TRUE(eventually(
      [&] {
        const char* stop = arm.lastStop();
        return stop != nullptr && std::string(stop).find("no RTDE data") != std::string::npos;
      },
      1.0));
  EXPECT_TRUE(eventually([&] { return arm.lastStop() == nullptr; }, 4.0)) << arm.lastStop();
  EXPECT_EQ(arm.stats().connections, 2U);
  EXPECT_EQ(emulator.stats().watchdog_stops, 1U);
}

/// Holds the first position it reads with a joint-space PD in torque, and keeps the effort read.
class TorqueHold final : public hardware::CycleController {
 public:
  [[nodiscard]] int dof() const noexcept override { return 6; }
  bool cycle(const JointState& state, double /*period_s*/,
             ActuatorCommand& command) noexcept override {
    if (!started_) {
      start_ = state.position;
      started_ = true;
    }
    command.mode = OutputMode::kTorque;
    command.effort = 100.0 * (start_ - state.position) - 5.0 * state.velocity;
    effort_ = state.effort;
    return true;
  }
  JointVector start_;
  JointVector effort_;

 private:
  bool started_ = false;
};

// direct_torque: the controller adds gravity, so a PD around the start holds the arm still with
// torques far below gravity's; the effort read is the drives' torque, gravity's on the shoulder.
TEST_F(UrBackend, TorqueCommandsOnTopOfTheControllersGravity) {
  UrArm arm(armFor(emulator, OutputMode::kTorque));
  EXPECT_TRUE(arm.compensatesGravity());
  UrClock clock(arm);
  TorqueHold controller;
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = kPeriod, .cycles = 500});
  (void)loop.run();
  EXPECT_EQ(emulator.state().program_mode, OutputMode::kTorque);
  EXPECT_LT((emulator.state().position - controller.start_).cwiseAbs().maxCoeff(), 2e-3)
      << "the arm sagged: gravity not compensated by the controller";
  ASSERT_TRUE(controller.effort_.allFinite()) << "PolyScope 5.23 reports joint torques";
  EXPECT_GT(std::abs(controller.effort_[1]), 10.0) << "the shoulder carries the arm's weight";
}

TEST(UrBackendSetup, APolyScopeBefore523GivesNoJointTorques) {
  UrEmulatorOptions old = freePorts();
  old.version = {5, 22, 1, 0};
  UrEmulator emulator(old);
  UrArm arm(armFor(emulator, OutputMode::kPosition));
  JointState state = JointState::zero(6);
  ASSERT_TRUE(eventually([&] { return arm.read(state); }, 1.0));
  EXPECT_TRUE(state.position.allFinite());
  EXPECT_TRUE(state.effort.array().isNaN().all()) << state.effort.transpose();
}

TEST(UrBackendSetup, TorqueCommandsNeedPolyScope523) {
  UrEmulatorOptions old = freePorts();
  old.version = {5, 22, 1, 0};
  UrEmulator emulator(old);
  try {
    UrArm arm(armFor(emulator, OutputMode::kTorque));
    FAIL() << "a 5.22 controller was taken for direct_torque";
  } catch (const hardware::BackendError& error) {
    EXPECT_NE(std::string(error.what()).find("5.23"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("5.22.1"), std::string::npos) << error.what();
  }
}

TEST(UrBackendSetup, NoControllerIsAClearError) {
  UrArmOptions options;
  options.robot_ip = "127.0.0.1";
  options.rtde_port = 1;  // nothing listens there
  try {
    UrArm arm(options);
    FAIL();
  } catch (const hardware::BackendError& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace comply::ur::test
