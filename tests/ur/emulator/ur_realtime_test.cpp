// The UR backend's control-thread side (the clock's wait for a package, read, the wrist sensor,
// the sample counter, the robot's stop, the answer, the hold) allocates no heap memory and takes
// no mutex: counted on the control thread over 500 cycles against the emulated controller.

#include <gtest/gtest.h>

#include "../../pipeline/mutex_lock_counter.hpp"
#include "allocation_counter.hpp"
#include "comply/hardware/control_loop.hpp"
#include "ur_emulator_support.hpp"

namespace comply::ur::test {
namespace {

/// Holds the first position it reads, asking for the robot's hold every tenth cycle.
class HoldingController final : public hardware::CycleController {
 public:
  [[nodiscard]] int dof() const noexcept override { return 6; }
  [[nodiscard]] OutputMode outputMode() const noexcept override { return OutputMode::kPosition; }
  bool cycle(const JointState& state, double /*period_s*/,
             ActuatorCommand& command) noexcept override {
    if (cycles_++ == 0) {
      first_ = state.position;
    }
    command.mode = OutputMode::kPosition;
    command.position = first_;
    saw_stop_ = saw_stop_ || state.robot_stop != nullptr;
    return cycles_ % 10 != 0;  // no output: the loop asks the hardware to hold
  }
  int cycles_ = 0;
  bool saw_stop_ = false;

 private:
  JointVector first_;
};

TEST(UrRealtime, TheControlThreadNeitherAllocatesNorLocks) {
  UrEmulator emulator(freePorts());
  UrArm arm(armFor(emulator, OutputMode::kPosition));
  UrClock clock(arm);
  HoldingController controller;
  hardware::ControlLoop warm(arm, controller, clock, {.period_s = 0.002, .cycles = 50});
  (void)warm.run();  // first-touch work (lazy binding, the loop's buffers) outside the count
  hardware::ControlLoop loop(arm, controller, clock, {.period_s = 0.002, .cycles = 500});
  comply::testing::AllocationCounter allocations;
  pipeline::test::MutexLockCounter locks;
  allocations.start();
  locks.start();
  const hardware::LoopStats stats = loop.run();
  const std::size_t locked = locks.stop();
  const std::size_t allocated = allocations.stop();
  EXPECT_EQ(allocated, 0U);
  EXPECT_EQ(locked, 0U);
  EXPECT_EQ(stats.cycles, 500U);
  EXPECT_EQ(stats.read_failures, 0U);
  EXPECT_GE(stats.held_cycles, 50U) << "the hold was not exercised";
  EXPECT_FALSE(controller.saw_stop_);
}

}  // namespace
}  // namespace comply::ur::test
