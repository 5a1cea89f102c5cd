// The robot's own stops through the UR path, with comply's controller in the loop: a protective
// stop and a lost link each end in a FAULT that names them, the arm held (pushed, it does not
// move); no reset leaves FAULT while the robot is stopped; once the stop is cleared (the
// dashboard's unlock, the link back), the backend sends the program again and a reset re-arms
// the controller, which yields to the push again.

#include <gtest/gtest.h>

#include <string>

#include "comply/ur/robot_status.hpp"
#include "ur_rig.hpp"

namespace comply::ur::test {
namespace {

constexpr double kPushN = 30.0;  // along base y: 1 cm on the file's 3000 N/m

class UrStop : public ::testing::Test {
 protected:
  // The backend's own link timeout (50 ms): a closed connection is found by it.
  UrStop()
      : emulator(waitingOptions()),
        rig(emulator, urConfig(OutputMode::kPosition), {"link_timeout_s=0.05"}) {}

  static UrEmulatorOptions waitingOptions() {
    UrEmulatorOptions options = freePorts();
    options.answer_wait_s = 0.5;
    return options;
  }

  void push(double force_n) {
    Vector6d wrench = Vector6d::Zero();
    wrench[1] = force_n;
    emulator.withPlant([&](sim::SimulatedRobot& plant) { plant.setExternalWrench(wrench); });
  }
  double tcpY() { return emulator.state().tcp.translation().y(); }
  pipeline::WrapperState controllerState() { return rig.wrapper.diagnostics().state; }
  bool faultsWith(const std::string& text) {
    return eventually(
        [&] {
          return controllerState() == pipeline::WrapperState::kFault &&
                 rig.wrapper.diagnostics().last_fault.find(text) != std::string::npos;
        },
        2.0);
  }

  /// Pushes twice as hard for 0.5 s: the held arm moves less than 1 mm.
  void expectHeld() {
    const double held = tcpY();
    push(2.0 * kPushN);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    EXPECT_LT(std::abs(tcpY() - held), 1e-3) << "the arm yielded while stopped";
  }

  /// A reset re-arms the controller; it yields to the push again.
  void expectRecovered() {
    const double held = tcpY();
    rig.wrapper.reset();
    EXPECT_TRUE(
        eventually([&] { return controllerState() == pipeline::WrapperState::kActive; }, 1.0));
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    EXPECT_GT(std::abs(tcpY() - held), 5e-3) << "the arm does not yield to the push after reset";
  }

  UrEmulator emulator;
  UrRig rig;
};

TEST_F(UrStop, AProtectiveStopIsAFaultThatNamesItAndRecoversAfterTheUnlock) {
  push(kPushN);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  emulator.protectiveStop();
  ASSERT_TRUE(faultsWith("robot: protective stop")) << rig.wrapper.diagnostics().last_fault;
  expectHeld();
  rig.wrapper.reset();  // refused: the robot is still stopped
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(controllerState(), pipeline::WrapperState::kFault);
  EXPECT_EQ(emulator.dashboard("unlock protective stop"), "Protective stop releasing");
  ASSERT_TRUE(eventually([&] { return rig.arm().lastStop() == nullptr; }, 3.0))
      << rig.arm().lastStop();
  EXPECT_EQ(rig.arm().stats().programs_sent, 2U);
  EXPECT_EQ(controllerState(), pipeline::WrapperState::kFault) << "re-armed without a reset";
  expectRecovered();
}

TEST_F(UrStop, ALostLinkIsAFaultThatNamesItTheProgramStopsTheArmAndItRecovers) {
  push(kPushN);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  emulator.closeConnections();
  ASSERT_TRUE(faultsWith("robot: the link to the UR controller is lost"))
      << rig.wrapper.diagnostics().last_fault;
  // Without answers the program's watchdog stopped the arm: it stands until the program runs.
  ASSERT_TRUE(eventually([&] { return emulator.stats().watchdog_stops == 1; }, 1.0));
  expectHeld();
  ASSERT_TRUE(eventually([&] { return rig.arm().lastStop() == nullptr; }, 3.0))
      << rig.arm().lastStop();
  EXPECT_EQ(rig.arm().stats().connections, 2U);
  EXPECT_EQ(controllerState(), pipeline::WrapperState::kFault) << "re-armed without a reset";
  expectRecovered();
}

}  // namespace
}  // namespace comply::ur::test
