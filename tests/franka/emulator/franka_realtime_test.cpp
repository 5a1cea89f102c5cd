// The Franka backend's control-thread side through comply's FCI client (the clock's wait for a
// state, read, the wrench estimate, the sample counter, the robot's stop, the torque) allocates
// no heap memory and takes no mutex: counted on the control thread over 1000 cycles of a running
// torque control against the emulated robot. (Starting and ending a torque control, a recovery
// and a change of collision thresholds run between such cycles and may do both.)

#include <gtest/gtest.h>

#include "../../pipeline/mutex_lock_counter.hpp"
#include "allocation_counter.hpp"
#include "comply/franka/franka_arm.hpp"
#include "comply/hardware/control_loop.hpp"
#include "fci_rig.hpp"

namespace comply::franka {
namespace {

/// Holds the first position it reads with a joint PD torque.
class HoldingController final : public hardware::CycleController {
 public:
  [[nodiscard]] int dof() const noexcept override { return 7; }
  bool cycle(const JointState& state, double /*period_s*/,
             ActuatorCommand& command) noexcept override {
    if (cycles_++ == 0) {
      first_ = state.position;
    }
    command.mode = OutputMode::kTorque;
    command.effort = 50.0 * (first_ - state.position) - 5.0 * state.velocity;
    saw_stop_ = saw_stop_ || state.robot_stop != nullptr;
    saw_wrench_ = saw_wrench_ || state.wrench_valid;
    saw_sequence_ = saw_sequence_ || state.sequence_valid;
    return true;
  }
  int cycles_ = 0;
  bool saw_stop_ = false;
  bool saw_wrench_ = false;
  bool saw_sequence_ = false;

 private:
  JointVector first_;
};

TEST(FrankaRealtime, TheControlThreadNeitherAllocatesNorLocks) {
  FrankaEmulator emulator(testing::emulatorOptions(0.5));
  FrankaArmOptions options;
  options.collision = frankaCollisionThresholds(20.0, 20.0);
  options.link_timeout_s = 0.6;  // the emulator waits up to 0.5 s for each command
  FrankaArm arm(testing::connect(emulator), options);
  FrankaClock clock(arm);
  HoldingController controller;
  hardware::ControlLoop warm(arm, controller, clock, {.period_s = 0.001, .cycles = 200});
  (void)warm.run();  // starts the torque control; first-touch work outside the count
  ASSERT_TRUE(emulator.state().torque_control);
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = 0.001, .cycles = 1000});
  comply::testing::AllocationCounter allocations;
  pipeline::test::MutexLockCounter locks;
  allocations.start();
  locks.start();
  const hardware::LoopStats stats = loop.run();
  const std::size_t locked = locks.stop();
  const std::size_t allocated = allocations.stop();
  EXPECT_EQ(allocated, 0U);
  EXPECT_EQ(locked, 0U);
  EXPECT_EQ(stats.cycles, 1000U);
  EXPECT_EQ(stats.read_failures, 0U);
  EXPECT_EQ(stats.write_failures, 0U);
  EXPECT_FALSE(controller.saw_stop_);
  EXPECT_TRUE(controller.saw_wrench_);
  EXPECT_TRUE(controller.saw_sequence_);
  EXPECT_EQ(arm.stats().controls, 1U);
  EXPECT_EQ(emulator.stats().lost, 0U);
}

}  // namespace
}  // namespace comply::franka
