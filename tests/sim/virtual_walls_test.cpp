// Virtual walls on the simulated FR3 (virtual_walls.hpp): a reference streamed toward a wall at
// 0.5 m/s, toward the face of a box a command sets at run time, and one leaving a box, do not
// carry the TCP through. Each run has its control: the same reference without the walls goes well
// past where the wall was.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include "governed_arm.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// Streams a reference from the start TCP along `direction` at `speed_m_per_s` until it is
/// `travel_m` out, then holds it, for `cycles`; returns the TCP's largest excursion along
/// `direction` past `limit_m` from the start (negative: it stayed short) and the TCP's speed
/// along it when it came within 50 mm of the limit.
struct Excursion {
  double past_m = -1.0;
  double arrival_speed_m_per_s = 0.0;
  double nearest_wall_m = 1e9;  ///< the walls stage's own distance, least over the run
  Eigen::Vector3d largest_force = Eigen::Vector3d::Zero();  ///< the barrier's, largest norm
};

/// `box`: set by the first command (the workspace group), corners relative to the start TCP.
Excursion stream(const pipeline::WrapperConfig& config, const Eigen::Vector3d& direction,
                 double speed_m_per_s, double travel_m, double limit_m, int cycles = 2000,
                 const std::optional<pipeline::WallBox>& box = std::nullopt) {
  Arm<> arm(config);
  const double period = arm.plant.controlPeriod();
  Excursion result;
  result.past_m = -limit_m;
  for (int cycle = 0; cycle < cycles; ++cycle) {
    const double along = std::min(speed_m_per_s * cycle * period, travel_m);
    CartesianCommand command = CartesianCommand::zero(arm.wrapper.dof());
    command.stamp_s = 1.0 + cycle * period;
    command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness;
    command.position = arm.start_tcp + along * direction;
    command.orientation = arm.wrapper.controller().modelData().tip_orientation;
    if (along < travel_m) {
      command.twist.head<3>() = speed_m_per_s * direction;
    }
    command.stiffness_translational = 2000.0 * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 100.0 * Eigen::Matrix3d::Identity();
    if (cycle == 0) {
      command.orientation = arm.wrapper.measuredPose().tcp_orientation;
      if (box) {
        command.fields = command.fields | CommandField::kWorkspace;
        command.workspace_min = arm.start_tcp + box->min;
        command.workspace_max = arm.start_tcp + box->max;
      }
    }
    EXPECT_TRUE(arm.wrapper.submit(command).accepted) << cycle;
    const double before = (arm.tcp() - arm.start_tcp).dot(direction);
    arm.cycle();
    const double now = (arm.tcp() - arm.start_tcp).dot(direction);
    if (before < limit_m - 0.05 && now >= limit_m - 0.05) {
      result.arrival_speed_m_per_s = (now - before) / period;
    }
    result.past_m = std::max(result.past_m, now - limit_m);
    const pipeline::VirtualWalls& walls = arm.wrapper.controller().walls();
    if (walls.enabled()) {
      result.nearest_wall_m = std::min(result.nearest_wall_m, walls.distance());
      if (walls.force().norm() > result.largest_force.norm()) {
        result.largest_force = walls.force();
      }
    }
  }
  EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
  return result;
}

TEST(VirtualWalls, ATcpDrivenAtAWallAtHalfAMetrePerSecondStopsWithinFiveMillimetres) {
  const Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  // Control: without the wall, the reference carries the TCP 7 cm past where the wall will be.
  const Excursion free_run = stream(config, direction, 0.5, 0.17, 0.10);
  EXPECT_GT(free_run.past_m, 0.05);
  EXPECT_GE(free_run.arrival_speed_m_per_s, 0.4);
  Arm<> probe(config);
  config.walls.planes.push_back(pipeline::WallPlane{probe.start_tcp + 0.10 * direction, direction});
  const Excursion walled = stream(config, direction, 0.5, 0.17, 0.10);
  EXPECT_GE(walled.arrival_speed_m_per_s, 0.4) << "the TCP did not arrive at speed";
  EXPECT_LE(walled.past_m, 0.005);
  // The stage's distance is the TCP's from the wall (one cycle apart), and the barrier pushed
  // straight back along -x.
  EXPECT_NEAR(walled.nearest_wall_m, -walled.past_m, 1e-3);
  EXPECT_LT(walled.largest_force.x(), -10.0);
  EXPECT_EQ(walled.largest_force.y(), 0.0);
  EXPECT_EQ(walled.largest_force.z(), 0.0);
  RecordProperty("penetration_mm", std::to_string(1e3 * walled.past_m));
  RecordProperty("arrival_speed_m_per_s", std::to_string(walled.arrival_speed_m_per_s));
  std::cout << "wall: arrival " << walled.arrival_speed_m_per_s << " m/s, past the wall "
            << 1e3 * walled.past_m << " mm (free run " << 1e3 * free_run.past_m << " mm)\n";
}

TEST(VirtualWalls, ABoxACommandSetsStopsTheTcpAsTheFilesWallDoes) {
  const Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  const pipeline::WrapperConfig config = simCartesianConfig("fr3");
  // The box's +x face 10 cm ahead of the start; the others 30 cm away. No walls in the file.
  const pipeline::WallBox box{Eigen::Vector3d(-0.3, -0.3, -0.3), Eigen::Vector3d(0.1, 0.3, 0.3)};
  const Excursion boxed = stream(config, direction, 0.5, 0.17, 0.10, 2000, box);
  EXPECT_GE(boxed.arrival_speed_m_per_s, 0.4) << "the TCP did not arrive at speed";
  EXPECT_LE(boxed.past_m, 0.005);
  EXPECT_NEAR(boxed.nearest_wall_m, -boxed.past_m, 1e-3);
  EXPECT_LT(boxed.largest_force.x(), -10.0);
  RecordProperty("penetration_mm", std::to_string(1e3 * boxed.past_m));
  std::cout << "commanded box: arrival " << boxed.arrival_speed_m_per_s << " m/s, past its face "
            << 1e3 * boxed.past_m << " mm\n";
}

TEST(VirtualWalls, ABoxKeepsTheTcpInsideUnderAReferenceThatLeavesIt) {
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  const Eigen::Vector3d direction = Eigen::Vector3d(0.0, -1.0, 1.0).normalized();
  // Leaving through the box's -y and +z faces, 6 cm from the start along each.
  const double face_m = 0.06 * std::sqrt(2.0);
  const Excursion free_run = stream(config, direction, 0.3, 0.15, face_m);
  EXPECT_GT(free_run.past_m, 0.03);
  Arm<> probe(config);
  const Eigen::Vector3d half(0.1, 0.06, 0.06);
  config.walls.boxes.push_back(pipeline::WallBox{probe.start_tcp - half, probe.start_tcp + half});
  const Excursion boxed = stream(config, direction, 0.3, 0.15, face_m);
  EXPECT_LE(boxed.past_m, 0.005 * std::sqrt(2.0));
  std::cout << "box: past the faces " << 1e3 * boxed.past_m / std::sqrt(2.0)
            << " mm each (free run " << 1e3 * free_run.past_m / std::sqrt(2.0) << " mm)\n";
}

TEST(VirtualWalls, ATcpActivatedPastAWallIsPulledBackInsideWithoutAFault) {
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  Arm<> probe(config);
  // The wall 3 cm behind the start along x: the TCP begins 3 cm past it, the reference (the
  // start pose, held) with it.
  config.walls.planes.push_back(pipeline::WallPlane{
      probe.start_tcp - Eigen::Vector3d(0.03, 0.0, 0.0), Eigen::Vector3d::UnitX()});
  Arm<> arm(config);
  const double period = arm.plant.controlPeriod();
  double first_distance = 0.0;
  double fastest_m_per_s = 0.0;
  Eigen::Vector3d previous = arm.tcp();
  for (int cycle = 0; cycle < 3000; ++cycle) {
    CartesianCommand command = CartesianCommand::zero(arm.wrapper.dof());
    command.stamp_s = 1.0 + cycle * period;
    command.fields = CommandField::kPosition | CommandField::kStiffness;
    command.position = arm.start_tcp;
    command.orientation = arm.wrapper.measuredPose().tcp_orientation;
    command.stiffness_translational = 2000.0 * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 100.0 * Eigen::Matrix3d::Identity();
    ASSERT_TRUE(arm.wrapper.submit(command).accepted) << cycle;
    arm.cycle();
    if (cycle == 0) {
      first_distance = arm.wrapper.controller().walls().distance();
    }
    fastest_m_per_s = std::max(fastest_m_per_s, (arm.tcp() - previous).norm() / period);
    previous = arm.tcp();
  }
  EXPECT_FALSE(arm.faulted()) << arm.wrapper.diagnostics().last_fault;
  EXPECT_NEAR(first_distance, -0.03, 1e-3);
  // Back on the allowed side, at the wall (the reference is projected onto it).
  const double final_distance = arm.wrapper.controller().walls().distance();
  EXPECT_GE(final_distance, -1e-3);
  EXPECT_LE(final_distance, 5e-3);
  std::cout << "activated 3 cm past a wall: " << 1e3 * final_distance
            << " mm inside after 3 s, fastest " << fastest_m_per_s << " m/s\n";
}
}  // namespace
}  // namespace comply::testing
