// Arc-length paths and the command stream along them: a circle's curvature and tangent, constant
// speed, the reference offset in the task frame, and the gains the stream sends.

#include "comply/task/path_command.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "comply/task/path.hpp"

namespace comply::task {
namespace {

Path circle(double radius, double angle) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 2000; ++i) {
    const double u = angle * i / 2000.0;
    points.emplace_back(radius * std::cos(u), radius * std::sin(u), 0.3);
  }
  return Path(points);
}

TEST(Path, CircleHasItsRadiusAndTangent) {
  const double radius = 0.1;
  const Path path = circle(radius, M_PI);
  EXPECT_NEAR(path.length(), M_PI * radius, 1e-5);
  for (const double s : {0.05, 0.15, 0.25}) {
    const double u = s / radius;
    EXPECT_LT((path.position(s) - Eigen::Vector3d(radius * std::cos(u), radius * std::sin(u), 0.3))
                  .norm(),
              1e-5);
    EXPECT_LT((path.tangent(s) - Eigen::Vector3d(-std::sin(u), std::cos(u), 0.0)).norm(), 1e-3);
    EXPECT_NEAR(path.curvatureVector(s).norm(), 1.0 / radius, 0.01 / radius);
    // Towards the centre.
    EXPECT_LT(
        path.curvatureVector(s).normalized().dot(path.position(s) - Eigen::Vector3d(0.0, 0.0, 0.3)),
        -0.99 * radius);
  }
  EXPECT_THROW(Path({Eigen::Vector3d::Zero()}), std::invalid_argument);
  EXPECT_THROW(Path({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}), std::invalid_argument);
}

TEST(Path, APointKilometresAwayIsRefusedBeforeAnySampleIsKept) {
  // 30 km at 0.5 mm would be 6e7 samples (1.4 GB); the limit is 500 m.
  try {
    (void)Path({Eigen::Vector3d(0.4, 0.0, 0.4), Eigen::Vector3d(0.4, 30485.0, 0.4)});
    FAIL() << "a 30 km path was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("above the limit of 1000000"), std::string::npos)
        << error.what();
  }
  try {
    // Just beyond: 1000002 samples, once printed "1e+06 samples ... above the limit of 1000000".
    (void)Path({Eigen::Vector3d::Zero(), Eigen::Vector3d(500.0001, 0.0, 0.0)});
    FAIL() << "a path of 500.0001 m was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("Path of 500.0001 m would need 1000002 samples"),
              std::string::npos)
        << error.what();
  }
  const Path longest({Eigen::Vector3d::Zero(), Eigen::Vector3d(499.0, 0.0, 0.0)});
  EXPECT_NEAR(longest.length(), 499.0, 1e-9);
}

TEST(PathCommand, MovesAtTheGivenSpeedWithTheOffsetInTheTaskFrame) {
  PathCommandOptions options;
  options.speed_m_per_s = 0.05;
  options.start_time_s = 1.0;
  options.frame = FrameSource::kFrenet;
  options.stiffness_translational = Eigen::Vector3d(1000.0, 50.0, 1000.0);
  options.offset_in_task_frame = Eigen::Vector3d(0.0, 0.02, 0.0);  // towards the centre
  PathCommand stream(circle(0.1, M_PI), options);

  const CartesianCommand before = stream.commandAt(0.5, 7);
  EXPECT_NEAR(before.position.x(), 0.1 - 0.02, 1e-4);  // start point, offset towards the centre
  EXPECT_EQ(before.twist.norm(), 0.0);

  const CartesianCommand during = stream.commandAt(3.0, 7);  // s = 0.1 m
  const double u = 0.1 / 0.1;
  const Eigen::Vector3d on_path(0.1 * std::cos(u), 0.1 * std::sin(u), 0.3);
  EXPECT_LT((during.position - 0.8 * on_path - Eigen::Vector3d(0, 0, 0.2 * 0.3)).norm(), 2e-4);
  EXPECT_NEAR(during.twist.head<3>().norm(), 0.05, 1e-9);
  EXPECT_GT(during.twist.head<3>().normalized().dot(Eigen::Vector3d(-std::sin(u), std::cos(u), 0)),
            0.999);
  // Gains in the task frame as given; the frame's second axis is the inward normal.
  EXPECT_EQ(during.stiffness_translational.diagonal(), options.stiffness_translational);
  EXPECT_EQ(during.damping_mode, DampingMode::kRatio);
  EXPECT_EQ(during.damping_ratio, Vector6d::Ones());
  const Eigen::Matrix3d frame = during.task_frame.toRotationMatrix();
  const Eigen::Vector3d inward = -(on_path - Eigen::Vector3d(0.0, 0.0, 0.3)).normalized();
  EXPECT_GT(frame.col(1).dot(inward), 0.999);

  const CartesianCommand after = stream.commandAt(100.0, 7);
  EXPECT_EQ(after.twist.norm(), 0.0);
  EXPECT_NEAR(after.position.x(), -0.1 + 0.02, 1e-4);
}

TEST(PathCommand, DarbouxNeedsASurfaceNormal) {
  PathCommandOptions options;
  options.frame = FrameSource::kDarboux;
  EXPECT_THROW(PathCommand(circle(0.1, 1.0), options), std::invalid_argument);
  options.surface_normal = [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitZ(); };
  PathCommand stream(circle(0.1, 1.0), options);
  const Eigen::Matrix3d frame = stream.commandAt(0.5, 6).task_frame.toRotationMatrix();
  EXPECT_LT((frame.col(1) - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
}

}  // namespace
}  // namespace comply::task
