// A sensor stream that freezes while the arm moves: the FAULT hold's gravity is that of the stale
// pose, and without damping (its velocity is stale too) the arm drifted 2.55 rad. The controller
// now asks the hardware to hold as well (CycleController::wantsHold -> HardwareInterface::hold):
// on the simulated arm, the brake stops it where the FAULT found it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "comply/hardware/control_loop.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "pose_step.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// The plant, seen through a sensor whose stream freezes after `frozen_after` reads; with or
/// without brakes, with or without the plant's sample counter (which freezes with the stream).
class FreezingSensor final : public hardware::HardwareInterface {
 public:
  FreezingSensor(sim::SimulatedRobot& plant, int frozen_after, bool brakes, bool counter = false)
      : plant_(plant), frozen_after_(frozen_after), brakes_(brakes), counter_(counter) {}
  [[nodiscard]] int dof() const noexcept override { return plant_.dof(); }
  bool read(JointState& state) noexcept override {
    if (reads_++ < frozen_after_) {
      plant_.read(last_);
      plant_.readSequence(sequence_);
    }
    state = last_;
    return true;
  }
  bool readSequence(std::uint64_t& sequence) noexcept override {
    sequence = sequence_;
    return counter_;
  }
  bool write(std::span<const double> torque) noexcept override { return plant_.write(torque); }
  bool hold() noexcept override { return brakes_ && plant_.hold(); }

 private:
  sim::SimulatedRobot& plant_;
  int frozen_after_;
  bool brakes_;
  bool counter_;
  int reads_ = 0;
  JointState last_;
  std::uint64_t sequence_ = 0;
};

struct Drift {
  bool faulted = false;
  double after_fault_rad = 0.0;  ///< largest joint motion from where the FAULT found the arm
};

Drift driftAfterAFrozenStream(bool brakes) {
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  config.stability_guard.enabled = false;  // the frozen stream is the subject here
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  sim::SimulatedClock clock(plant);
  FreezingSensor sensor(plant, 150, brakes);
  pipeline::CartesianWrapper wrapper(config);
  JointState state = JointState::zero(plant.dof());
  sensor.read(state);
  wrapper.activate(state);
  const CartesianCommand target = testing::poseStep(wrapper, Eigen::Vector3d(0.0, 0.05, 0.0));
  EXPECT_TRUE(wrapper.submit(target).accepted);  // the arm moves, then its stream freezes

  hardware::ControlLoop loop(sensor, wrapper, clock, {.period_s = plant.controlPeriod()});
  Drift drift;
  JointState at_fault = JointState::zero(plant.dof());
  JointState now = JointState::zero(plant.dof());
  for (int cycle = 0; cycle < 2500; ++cycle) {
    loop.runOnce();
    const bool fault = wrapper.diagnostics().state == pipeline::WrapperState::kFault;
    plant.read(now);
    if (fault && !drift.faulted) {
      drift.faulted = true;
      at_fault = now;
    }
    if (drift.faulted) {
      drift.after_fault_rad =
          std::max(drift.after_fault_rad, (now.position - at_fault.position).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_NE(wrapper.diagnostics().last_fault.find("stale sensor stream"), std::string::npos)
      << wrapper.diagnostics().last_fault;
  return drift;
}

TEST(FrozenSensorHold, TheBrakesHoldTheArmWhereTheFaultFoundIt) {
  const Drift without = driftAfterAFrozenStream(false);
  const Drift with = driftAfterAFrozenStream(true);
  ASSERT_TRUE(without.faulted);
  ASSERT_TRUE(with.faulted);
  RecordProperty("drift_without_brakes_rad", std::to_string(without.after_fault_rad));
  RecordProperty("drift_with_brakes_rad", std::to_string(with.after_fault_rad));
  EXPECT_GT(without.after_fault_rad, 0.01) << "the gravity hold at a stale pose drifts";
  EXPECT_LT(with.after_fault_rad, 0.002) << "braked, the arm stays where the FAULT found it";
}

TEST(SimulatedRobotCounter, AdvancesOncePerControlPeriodWhateverTheArmDoes) {
  const pipeline::WrapperConfig config = simCartesianConfig("fr3");
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  JointState state = JointState::zero(plant.dof());
  std::uint64_t first = 0;
  plant.read(state);
  ASSERT_TRUE(plant.readSequence(first));
  plant.hold();  // braked: the samples repeat, the counter does not
  for (int period = 1; period <= 5; ++period) {
    plant.step();
    plant.read(state);
    std::uint64_t sequence = 0;
    plant.readSequence(sequence);
    EXPECT_EQ(sequence, first + static_cast<std::uint64_t>(period));
  }
}

/// The arm at rest, its stream frozen, then pushed by hand: the samples repeat a pose at rest,
/// which the samples alone cannot tell from an arm at rest. The plant's sample counter, frozen
/// with the stream, can.
struct PushedWhileFrozen {
  bool faulted = false;
  std::string fault;
  double moved_rad = 0.0;  ///< how far the push moved the arm before the FAULT (or the end)
};

PushedWhileFrozen pushWhileFrozen(bool counter) {
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  config.stability_guard.enabled = false;
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  sim::SimulatedClock clock(plant);
  FreezingSensor sensor(plant, 100, /*brakes=*/true, counter);
  pipeline::CartesianWrapper wrapper(config);
  JointState state = JointState::zero(plant.dof());
  sensor.read(state);
  wrapper.activate(state);
  const JointState start = state;
  hardware::ControlLoop loop(sensor, wrapper, clock, {.period_s = plant.controlPeriod()});
  PushedWhileFrozen result;
  JointState now = JointState::zero(plant.dof());
  for (int cycle = 0; cycle < 1000 && !result.faulted; ++cycle) {
    if (cycle == 150) {
      plant.setExternalWrench((Vector6d() << 0.0, 30.0, 0.0, 0.0, 0.0, 0.0).finished());
    }
    loop.runOnce();
    result.faulted = wrapper.diagnostics().state == pipeline::WrapperState::kFault;
    plant.read(now);
    result.moved_rad = (now.position - start.position).cwiseAbs().maxCoeff();
  }
  result.fault = wrapper.diagnostics().last_fault;
  return result;
}

TEST(FrozenSensorHold, ThePlantsCounterTellsAFrozenStreamFromAnArmAtRest) {
  const PushedWhileFrozen samples_only = pushWhileFrozen(false);
  EXPECT_FALSE(samples_only.faulted) << "a repeated sample at rest passes the sample checks";
  EXPECT_GT(samples_only.moved_rad, 0.05) << "and the push moves the arm unseen";

  const PushedWhileFrozen with_counter = pushWhileFrozen(true);
  ASSERT_TRUE(with_counter.faulted);
  EXPECT_NE(with_counter.fault.find("sample counter has not advanced"), std::string::npos)
      << with_counter.fault;
  RecordProperty("moved_before_fault_rad", std::to_string(with_counter.moved_rad));
}

}  // namespace
}  // namespace comply::testing
