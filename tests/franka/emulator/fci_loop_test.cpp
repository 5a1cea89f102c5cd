// A minute of the emulated robot's 1 kHz states, every one answered in order by comply's FCI
// client holding the arm with a joint PD (on top of the robot's gravity compensation).

#include <gtest/gtest.h>

#include <chrono>

#include "fci_rig.hpp"

namespace comply::franka {
namespace {

TEST(FciLoop, SixtySecondsOfStatesWithoutALostCycle) {
  // The emulator waits for each answer (answer_wait_s): a busy host's scheduling does not count
  // against the client; an answer after its cycle would still count as late.
  FrankaEmulator robot(testing::emulatorOptions(0.5));
  auto session = testing::connect(robot);
  FrankaSample sample;
  ASSERT_EQ(session->startTorqueControl(sample), "");  // the first torque answers its state
  const std::array<double, 7> hold_q = sample.q;
  std::uint64_t last = sample.time_ms;
  std::uint64_t gaps = 0;
  std::uint64_t states = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  double worst_error = 0.0;
  while (std::chrono::steady_clock::now() < until) {
    std::array<double, 7> torque{};
    for (std::size_t j = 0; j < 7; ++j) {
      torque[j] = 100.0 * (hold_q[j] - sample.q[j]) - 10.0 * sample.dq[j];
      worst_error = std::max(worst_error, std::abs(hold_q[j] - sample.q[j]));
    }
    ASSERT_TRUE(session->writeTorque(torque));
    ASSERT_TRUE(session->read(sample, 1.0)) << session->failure();
    ASSERT_EQ(sample.robot_mode, fci::RobotMode::kMove);
    gaps += sample.time_ms - last - 1;
    last = sample.time_ms;
    ++states;
  }
  ASSERT_EQ(session->stopTorqueControl(), "");
  const FrankaEmulatorStats stats = robot.stats();
  std::printf(
      "states %llu, answered %llu, late %llu, lost %llu, gaps %llu, worst joint error %.4f rad\n",
      static_cast<unsigned long long>(states), static_cast<unsigned long long>(stats.answered),
      static_cast<unsigned long long>(stats.late), static_cast<unsigned long long>(stats.lost),
      static_cast<unsigned long long>(gaps), worst_error);
  EXPECT_EQ(gaps, 0U);
  EXPECT_EQ(stats.lost, 0U);
  EXPECT_EQ(stats.reflexes, 0U);
  EXPECT_GE(states, 20000U);  // a minute at 1 kHz, and a busy host's stalls
  EXPECT_LT(worst_error, 0.01);
}

}  // namespace
}  // namespace comply::franka
