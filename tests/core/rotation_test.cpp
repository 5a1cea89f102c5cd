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

TEST(Skew, IsTheCrossProductAndAntisymmetric) {
  const Eigen::Vector3d v(0.3, -1.2, 2.5);
  const Eigen::Vector3d w(-0.7, 0.4, 1.1);
  EXPECT_LT((skew(v) * w - v.cross(w)).norm(), 1e-15);
  EXPECT_TRUE((skew(v) + skew(v).transpose()).isZero(0.0));
}

TEST(QuaternionExp, UndoesTheLogarithm) {
  const Eigen::Vector3d axis = Eigen::Vector3d(-0.4, 0.9, 0.2).normalized();
  // 1e-13 rad takes the small-angle branch of both.
  for (const double angle : {0.0, 1e-13, 1e-7, 0.3, 1.5, 3.1}) {
    const Eigen::Quaterniond q = rotationAbout(axis, angle);
    const Eigen::Quaterniond back = quaternionExp(quaternionLog(q));
    EXPECT_LT((back.coeffs() - q.coeffs()).norm(), 1e-15) << "angle " << angle;
    const Eigen::Vector3d phi = angle * axis;
    EXPECT_LT((quaternionLog(quaternionExp(phi)) - phi).norm(), 1e-15) << "angle " << angle;
  }
}

TEST(QuaternionExp, IsContinuousAcrossItsSmallAngleBranch) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -2.0).normalized();
  const Eigen::Quaterniond below = quaternionExp(0.999e-12 * axis);
  const Eigen::Quaterniond above = quaternionExp(1.001e-12 * axis);
  EXPECT_DOUBLE_EQ(below.w(), 1.0);
  EXPECT_LT((below.vec() - 0.4995e-12 * axis).norm(), 1e-26);
  EXPECT_LT((above.coeffs() - below.coeffs()).norm(), 2e-15);
}

/// The body angular velocity of Exp(phi + t direction) at t = 0, by a central difference.
Eigen::Vector3d bodyRateByDifference(const Eigen::Vector3d& phi, const Eigen::Vector3d& direction) {
  constexpr double kStep = 1e-6;
  const Eigen::Quaterniond before = quaternionExp(phi - kStep * direction);
  const Eigen::Quaterniond after = quaternionExp(phi + kStep * direction);
  return quaternionLog(before.conjugate() * after) / (2.0 * kStep);
}

TEST(RightJacobian, MapsTheRateOfPhiToTheBodyAngularVelocity) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.5, -0.3, 0.8).normalized();
  const Eigen::Vector3d direction(0.2, 1.0, -0.6);
  // 1e-7 rad takes the series; the others the closed form.
  for (const double angle : {1e-7, 0.3, 1.5, 2.8}) {
    const Eigen::Vector3d phi = angle * axis;
    EXPECT_LT((rightJacobian(phi) * direction - bodyRateByDifference(phi, direction)).norm(), 1e-8)
        << "angle " << angle;
  }
}

TEST(RightJacobian, TimesItsInverseIsTheIdentity) {
  const Eigen::Vector3d axis = Eigen::Vector3d(-0.1, 0.7, 0.7).normalized();
  for (const double angle : {0.0, 1e-7, 0.3, 1.5, 3.0}) {
    const Eigen::Vector3d phi = angle * axis;
    const Eigen::Matrix3d product = rightJacobian(phi) * rightJacobianInverse(phi);
    EXPECT_LT((product - Eigen::Matrix3d::Identity()).norm(), 1e-12) << "angle " << angle;
  }
}

TEST(RightJacobian, ItsSeriesMeetsTheClosedFormAtTheBranch) {
  // The closed forms are only good to about 1e-10 here (1 - cos(1e-6) keeps four digits), so
  // that is what the two sides can agree to; a wrong first-order term would differ by 1e-6.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.6, 0.0, -0.8);
  const Eigen::Vector3d series = 0.999999e-6 * axis;
  const Eigen::Vector3d closed = 1.000001e-6 * axis;
  EXPECT_LT((rightJacobian(series) - rightJacobian(closed)).norm(), 1e-9);
  EXPECT_LT((rightJacobianInverse(series) - rightJacobianInverse(closed)).norm(), 1e-9);
  EXPECT_GT((rightJacobian(series) - Eigen::Matrix3d::Identity()).norm(), 1e-7);
}

}  // namespace
}  // namespace comply
