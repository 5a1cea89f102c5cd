// Friction and soft-limit torques against their formulas. Inputs are chosen so every exponential
// and tanh has a closed form (exp(-ln 3) = 1/3, tanh(ln 2) = 3/5): the expected values are exact.

#include "comply/pipeline/compensation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "command_bits.hpp"

namespace comply::pipeline {
namespace {

using test::joints;

constexpr double kTight = 1e-12;

FrictionParameters sigmoid(std::vector<double> phi1, std::vector<double> phi2,
                           std::vector<double> phi3) {
  FrictionConfig friction;
  friction.model = FrictionModel::kSigmoid;
  friction.phi1 = std::move(phi1);
  friction.phi2 = std::move(phi2);
  friction.phi3 = std::move(phi3);
  return compileFriction(friction, static_cast<int>(friction.phi1.size()));
}

FrictionParameters viscousCoulomb(std::vector<double> viscous, std::vector<double> coulomb,
                                  double smoothing_velocity) {
  FrictionConfig friction;
  friction.model = FrictionModel::kViscousCoulomb;
  friction.viscous = std::move(viscous);
  friction.coulomb = std::move(coulomb);
  friction.smoothing_velocity = smoothing_velocity;
  return compileFriction(friction, static_cast<int>(friction.viscous.size()));
}

TEST(FrictionTorque, NoneIsZeroAndResizedToTheVelocity) {
  JointVector torque = joints({7.0, 7.0});  // stale content and size from a previous cycle
  frictionTorque(FrictionParameters{}, joints({1.0, -2.0, 3.0}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_EQ(torque, JointVector::Zero(3));
}

TEST(FrictionTorque, SigmoidMatchesClosedFormPerJoint) {
  const double ln3 = std::log(3.0);
  // joint 0: 1/(1 + 1/3) - 1/2 = 1/4
  // joint 1: dq = 0 gives zero for any offset phi3 (the model is shifted to pass through 0)
  // joint 2: 4/(1 + 1) - 4/(1 + 1/3) = 2 - 3 = -1
  const FrictionParameters friction =
      sigmoid({1.0, 2.0, 4.0}, {1.0, 2.0, 1.0}, {0.0, ln3 / 2, ln3});
  JointVector torque;
  frictionTorque(friction, joints({ln3, 0.0, -ln3}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_NEAR(torque[0], 0.25, kTight);
  EXPECT_NEAR(torque[1], 0.0, kTight);
  EXPECT_NEAR(torque[2], -1.0, kTight);
}

TEST(FrictionTorque, SigmoidSaturatesAtPhi1MinusItsOffset) {
  // Far from zero velocity the first term reaches phi1 (or 0); with phi3 = 0 the offset is phi1/2.
  const FrictionParameters friction = sigmoid({0.8, 0.8}, {5.0, 5.0}, {0.0, 0.0});
  JointVector torque;
  frictionTorque(friction, joints({1e3, -1e3}), torque);
  EXPECT_NEAR(torque[0], 0.4, kTight);
  EXPECT_NEAR(torque[1], -0.4, kTight);
}

TEST(FrictionTorque, ViscousCoulombMatchesClosedForm) {
  const double ln2 = std::log(2.0);
  // tanh(ln 2) = 3/5: joint 0 is 0.5 * 0.01 ln2 + 2 * 0.6; joint 1 the same mirrored.
  const FrictionParameters friction = viscousCoulomb({0.5, 0.5, 3.0}, {2.0, 2.0, 1.0}, 0.01);
  JointVector torque;
  frictionTorque(friction, joints({0.01 * ln2, -0.01 * ln2, 0.0}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_NEAR(torque[0], 0.005 * ln2 + 1.2, kTight);
  EXPECT_NEAR(torque[1], -(0.005 * ln2 + 1.2), kTight);
  EXPECT_NEAR(torque[2], 0.0, kTight);  // smooth through zero: no Coulomb step at rest
}

TEST(FrictionTorque, ViscousCoulombScalesWithSmoothingVelocity) {
  const double ln2 = std::log(2.0);
  // The same dq is 'half way up' the tanh for v = 0.02 but fully saturated for v = 1e-4.
  JointVector wide;
  frictionTorque(viscousCoulomb({0.0}, {1.0}, 0.02), joints({0.02 * ln2}), wide);
  EXPECT_NEAR(wide[0], 0.6, kTight);
  JointVector sharp;
  frictionTorque(viscousCoulomb({0.0}, {1.0}, 1e-4), joints({0.02 * ln2}), sharp);
  EXPECT_NEAR(sharp[0], 1.0, kTight);
}

/// One joint per row of the spring-damper cases, each with its own limits and gains.
struct SoftLimitFixture {
  SoftLimitConfig config;
  JointVector lower = joints({-1.0, -2.0, -1.0});
  JointVector upper = joints({1.0, 2.0, 1.0});

  SoftLimitFixture() {
    config.margin = {0.25, 0.5, 0.25};
    config.stiffness = {100.0, 40.0, 100.0};
    config.damping = {4.0, 2.0, 4.0};
  }
};

TEST(SoftLimitTorque, SpringDamperPushesBackNearTheUpperLimit) {
  const SoftLimitFixture f;
  JointVector torque;
  // joint 0: 0.125 into the band, moving out: -100 * 0.125 - 4 * 0.5 = -14.5
  // joint 1: beyond the limit (2.25 vs start 1.5), moving back: -40 * 0.75 - 2 * (-1) = -28
  softLimitTorque(compileSoftLimits(f.config, f.lower, f.upper), joints({0.875, 2.25, 0.0}),
                  joints({0.5, -1.0, 0.0}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_NEAR(torque[0], -14.5, kTight);
  EXPECT_NEAR(torque[1], -28.0, kTight);
  EXPECT_NEAR(torque[2], 0.0, kTight);
}

TEST(SoftLimitTorque, SpringDamperPushesBackNearTheLowerLimit) {
  const SoftLimitFixture f;
  JointVector torque;
  // joint 0: at the limit, start -0.75: -100 * (-0.25) - 4 * (-1) = 29
  // joint 1: start -1.5, q = -1.75: -40 * (-0.25) - 2 * 0.5 = 9
  softLimitTorque(compileSoftLimits(f.config, f.lower, f.upper), joints({-1.0, -1.75, 0.0}),
                  joints({-1.0, 0.5, 0.0}), torque);
  EXPECT_NEAR(torque[0], 29.0, kTight);
  EXPECT_NEAR(torque[1], 9.0, kTight);
  EXPECT_NEAR(torque[2], 0.0, kTight);
}

TEST(SoftLimitTorque, ZeroInsideTheFreeBandEvenWhenMoving) {
  const SoftLimitFixture f;
  JointVector torque = joints({5.0});  // stale content must not survive
  // The band edges themselves (0.75, -1.5) are still free: the spring engages strictly beyond.
  softLimitTorque(compileSoftLimits(f.config, f.lower, f.upper), joints({0.75, -1.5, 0.5}),
                  joints({3.0, -3.0, 10.0}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_EQ(torque, JointVector::Zero(3));
}

TEST(SoftLimitTorque, DisabledIsZeroEvenBeyondTheLimits) {
  SoftLimitFixture f;
  f.config.enabled = false;
  JointVector torque;
  softLimitTorque(compileSoftLimits(f.config, f.lower, f.upper), joints({1.5, -3.0, 0.9}),
                  joints({1.0, -1.0, 1.0}), torque);
  ASSERT_EQ(torque.size(), 3);
  EXPECT_EQ(torque, JointVector::Zero(3));
}

}  // namespace
}  // namespace comply::pipeline
