#include "comply/core/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace comply {
namespace {

Eigen::Quaterniond rotationAbout(const Eigen::Vector3d& axis, double angle_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, axis.normalized()));
}

TEST(QuaternionLog, IsAxisTimesAngle) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  for (const double angle : {0.0, 1e-9, 0.3, 1.5, 3.0}) {
    const Eigen::Vector3d phi = quaternionLog(rotationAbout(axis, angle));
    EXPECT_LT((phi - angle * axis).norm(), 1e-12) << "angle " << angle;
  }
}

TEST(QuaternionLog, NegatedQuaternionGivesTheLongWayRound) {
  // -q is the same rotation; with w < 0 the log is the same rotation the long way round, which is
  // why orientationError() picks the w >= 0 hemisphere first.
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  const Eigen::Quaterniond q = rotationAbout(axis, 0.4);
  const Eigen::Quaterniond negated(-q.w(), -q.x(), -q.y(), -q.z());
  EXPECT_LT((quaternionLog(negated) - (0.4 - 2.0 * M_PI) * axis).norm(), 1e-12);
}

TEST(OrientationError, PointsFromCurrentToDesiredInTheBaseFrame) {
  const Eigen::Quaterniond current = rotationAbout(Eigen::Vector3d(0.3, 1.0, -0.2), 1.1);
  // desired = current turned by 0.2 rad about the base x axis.
  const Eigen::Quaterniond desired = rotationAbout(Eigen::Vector3d::UnitX(), 0.2) * current;
  EXPECT_LT((orientationError(current, desired) - 0.2 * Eigen::Vector3d::UnitX()).norm(), 1e-12);
}

TEST(OrientationError, IsIndependentOfTheQuaternionSigns) {
  const Eigen::Quaterniond current = rotationAbout(Eigen::Vector3d(1.0, 1.0, 0.0), 0.7);
  const Eigen::Quaterniond desired = rotationAbout(Eigen::Vector3d(0.0, 1.0, 1.0), -0.4);
  const Eigen::Quaterniond desired_negated(-desired.w(), -desired.x(), -desired.y(), -desired.z());
  const Eigen::Quaterniond current_negated(-current.w(), -current.x(), -current.y(), -current.z());
  const Eigen::Vector3d reference = orientationError(current, desired);
  EXPECT_LT((orientationError(current, desired_negated) - reference).norm(), 1e-12);
  EXPECT_LT((orientationError(current_negated, desired) - reference).norm(), 1e-12);
  EXPECT_LT(reference.norm(), M_PI + 1e-12);
}

TEST(OrientationError, ZeroAtTheTarget) {
  const Eigen::Quaterniond q = rotationAbout(Eigen::Vector3d(0.2, -0.1, 0.9), 2.5);
  EXPECT_LT(orientationError(q, q).norm(), 1e-15);
}

}  // namespace
}  // namespace comply
