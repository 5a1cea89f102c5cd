// How a task file's reference goes from one waypoint to the next (host/task_source.hpp): linear
// at a constant speed, whose velocity steps at both ends (and the law's damping torque with it),
// or smooth, a minimum-jerk profile that starts and ends at rest, with the velocity its position
// has.

#include <gtest/gtest.h>

#include <cmath>

#include "comply/host/task_source.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

host::Trajectory trajectory(const std::string& interpolate) {
  const host::TaskFile task = taskFromYaml(
      "task:\n  waypoints:\n    - time_s: 2.0\n      position: [0.5, 0.0, 0.4]\n"
      "      orientation: [0.0, 0.0, 0.19866933, 0.98006658]\n      interpolate: " +
          interpolate + "\n",
      true, 7);
  host::Reference start;
  start.position = Eigen::Vector3d(0.4, 0.0, 0.4);
  return host::Trajectory(task, start);
}

TEST(TaskInterpolation, SmoothStartsAndEndsAtRestAndItsVelocityIsItsPositionsRate) {
  const host::Trajectory smooth = trajectory("smooth");
  EXPECT_LT(smooth.at(0.0).twist.norm(), 1e-12);
  EXPECT_LT(smooth.at(2.0 - 1e-9).twist.norm(), 1e-6);
  // Half way at half time, at 1.875 times the mean speed (0.05 m/s, 0.2 rad/s).
  const host::Reference middle = smooth.at(1.0);
  EXPECT_NEAR(middle.position.x(), 0.45, 1e-12);
  EXPECT_NEAR(middle.twist[0], 1.875 * 0.05, 1e-12);
  EXPECT_NEAR(middle.twist[5], 1.875 * 0.2, 1e-6);
  for (const double t : {0.3, 0.9, 1.6}) {
    const double h = 1e-6;
    const Eigen::Vector3d rate =
        (smooth.at(t + h).position - smooth.at(t - h).position) / (2.0 * h);
    EXPECT_NEAR((rate - smooth.at(t).twist.head<3>()).norm(), 0.0, 1e-8) << t;
    const Eigen::AngleAxisd turn(smooth.at(t + h).orientation *
                                 smooth.at(t - h).orientation.conjugate());
    EXPECT_NEAR(turn.angle() / (2.0 * h), smooth.at(t).twist.tail<3>().norm(), 1e-6) << t;
  }
}

TEST(TaskInterpolation, LinearStepsItsVelocityAtBothEnds) {
  const host::Trajectory linear = trajectory("linear");
  EXPECT_NEAR(linear.at(0.0).twist[0], 0.05, 1e-12);  // from rest to 0.05 m/s at once
  EXPECT_NEAR(linear.at(1.999).twist[0], 0.05, 1e-12);
  EXPECT_NEAR(linear.at(2.0).twist.norm(), 0.0, 1e-12);
  const host::Trajectory step = trajectory("step");
  EXPECT_NEAR(step.at(1.0).position.x(), 0.4, 1e-12);
}

TEST(TaskInterpolation, AnUnknownInterpolationIsNamed) {
  try {
    (void)trajectory("cubic");
    ADD_FAILURE() << "cubic was taken";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("must be linear, smooth or step"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace comply::testing
