// The simulated hardware's cycle (read, write, step) allocates no heap memory, with contact in the
// scene and measurement noise on, for torque motors and for every other kind of drive with the
// wrist sensor read: a control loop on the simulator is as allocation-free as on a real arm.
// Counted by the interposed allocator of tests/support.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "allocation_counter.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "plant_commands.hpp"

namespace comply::testing {
namespace {

TEST(SimulatedRobotAllocation, ReadWriteStepAllocateNothing) {
  sim::PlantOptions options;
  options.substeps = 2;
  options.position_noise_rad = 1e-5;
  options.velocity_noise_rad_per_s = 1e-4;
  options.scene.objects.push_back(std::filesystem::path(COMPLY_TEST_SOURCE_DIR) / "examples" /
                                  "sim" / "table.xml");
  sim::SimulatedRobot robot(model::loadRobotDescription("fr3"), options);
  JointState state = JointState::zero(robot.dof());
  std::vector<double> torque(static_cast<std::size_t>(robot.dof()), 0.5);

  AllocationCounter counter;
  counter.start();
  for (int cycle = 0; cycle < 2000; ++cycle) {
    robot.read(state);
    robot.write(torque);
    robot.step();
    (void)robot.toolContactWrench();
    (void)robot.tcpPose();
  }
  EXPECT_EQ(counter.stop(), 0U);
  EXPECT_GT(robot.simTime(), 1.99);  // the loop did run
}

TEST(SimulatedRobotAllocation, EveryKindOfDriveAndTheWristSensorAllocateNothing) {
  for (const OutputMode mode :
       {OutputMode::kJointPd, OutputMode::kPosition, OutputMode::kVelocity}) {
    SCOPED_TRACE(std::string(toString(mode)));
    sim::PlantOptions options;
    options.actuation = mode;
    options.substeps = 2;
    sim::SimulatedRobot robot(model::loadRobotDescription("ur5e"), options);
    JointState state = JointState::zero(robot.dof());
    ActuatorCommand command = holdWhereItIs(robot, mode);
    command.stiffness.setConstant(50.0);
    Vector6d wrench;
    AllocationCounter counter;
    counter.start();
    for (int cycle = 0; cycle < 1000; ++cycle) {
      robot.read(state);
      (void)robot.readWrench(wrench);
      command.velocity[0] = 0.1 * std::sin(cycle * 1e-2);
      robot.writeCommand(command);
      robot.step();
    }
    EXPECT_EQ(counter.stop(), 0U);
    EXPECT_TRUE(wrench.allFinite());
  }
}

}  // namespace
}  // namespace comply::testing
