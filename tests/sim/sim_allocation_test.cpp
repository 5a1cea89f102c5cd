// The simulated hardware's cycle (read, write, step) allocates no heap memory, with contact in the
// scene and measurement noise on: a control loop on the simulator is as allocation-free as on a
// real arm. Counted by the interposed allocator of tests/support.

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/sim/simulated_robot.hpp"

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

}  // namespace
}  // namespace comply::testing
