// Compensation is real, not assumed: with zero stiffness and damping the only thing holding each
// simulated arm at home is the wrapper's gravity compensation. With it the TCP stays put; without
// it the arm falls. The plant keeps its joint friction (robot.yaml), as a real arm would; a third
// run without it shows that friction is not what holds the arm.

#include <gtest/gtest.h>

#include "comply/host/controller_setup.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/model/robot_description.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

constexpr double kHoldSeconds = 5.0;

/// Largest TCP distance from its start position over the run [m].
double maxDrift(const std::string& robot, bool gravity_compensation, bool plant_friction = true) {
  host::SimRunOptions run;
  run.config = host::controllerConfig(robot, "joint_impedance");
  run.config.gravity_compensation = gravity_compensation;
  // Falling freely is the point of the run without compensation: the stability guard would stop
  // the fall (a joint past its limit) and hold the arm.
  run.config.stability_guard.enabled = false;
  run.config.initial_joint.stiffness.setZero();
  run.config.initial_joint.damping.setZero();
  run.task = taskFromYaml("task: {waypoints: [{time_s: 0.0}]}", false, run.config.dof);
  run.duration_s = kHoldSeconds;
  run.plant_joint_dynamics = plant_friction;
  const host::SimResult result = host::runSimulation(run);
  EXPECT_EQ(result.summary.faults, 0U);
  EXPECT_EQ(result.log.size(), static_cast<std::size_t>(kHoldSeconds * 1000.0));
  double drift = 0.0;
  for (const Eigen::Vector3d& position : result.log.tcp_position) {
    drift = std::max(drift, (position - result.log.tcp_position.front()).norm());
  }
  return drift;
}

class GravityCompensation : public ::testing::TestWithParam<std::string> {};

TEST_P(GravityCompensation, HoldsHomeWithinOneMillimetreAndFallsWithout) {
  const double held = maxDrift(GetParam(), true);
  const double unheld = maxDrift(GetParam(), false);
  // Without joint friction and damping in the plant nothing but the compensation holds the arm:
  // the static friction above cannot be what kept it in place.
  const double held_frictionless = maxDrift(GetParam(), true, false);
  RecordProperty("drift_with_compensation_mm", std::to_string(1e3 * held));
  RecordProperty("drift_without_compensation_mm", std::to_string(1e3 * unheld));
  EXPECT_LT(held, 1e-3) << GetParam() << " drifted " << 1e3 * held << " mm";
  EXPECT_LT(held_frictionless, 1e-3)
      << GetParam() << " drifted " << 1e3 * held_frictionless << " mm with a frictionless plant";
  EXPECT_GT(unheld, 0.05) << GetParam() << " only moved " << 1e3 * unheld
                          << " mm without gravity compensation";
}

// Every robot on the search path: a new robot folder is covered with no line to add.
INSTANTIATE_TEST_SUITE_P(Robots, GravityCompensation,
                         ::testing::ValuesIn(model::availableRobots()));

}  // namespace
}  // namespace comply::testing
