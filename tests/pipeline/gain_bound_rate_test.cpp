// The gain bound's torque-rate part (pipeline/gain_bound.hpp): sqrt(K / m) <= R / tau, with R the
// torque-rate limit and tau the swing the law's torque must pass through it without a limit
// cycle, against the model the header states: the sampled loop m x'' = u, u = -K x - D x' from
// the sample, held for a period (and one more period of delay on a real driver), changed by at
// most R T per period. Hand numbers on a two-joint bound: R = 1000 and 800 N m/s, tau = 5 N m,
// so w_n <= 160 rad/s on a Cartesian gain (the lower R), against c / T = 350 rad/s.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

#include "command_bits.hpp"
#include "comply/pipeline/gain_bound.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kPeriod = 1e-3;
constexpr double kSwingNm = 5.0;

GainBound rateBound() {
  GainBound bound;
  bound.translational_mass_kg = 2.0;
  bound.rotational_inertia_kg_m2 = 0.04;
  bound.joint_inertia = joints({0.3, 0.05});
  bound.joint_lever_sq = joints({0.64, 0.01});
  bound.joint_axis_sq = joints({1.0, 1.0});
  bound.torque_rate_limit = joints({1000.0, 800.0});
  bound.rate_limit_swing_nm = kSwingNm;
  bound.robot = "two-joint";
  return bound;
}

CartesianCommand stiffness(double translational, double rotational) {
  CartesianCommand command = CartesianCommand::zero(2);
  command.fields = CommandField::kStiffness;
  command.stiffness_translational = translational * Eigen::Matrix3d::Identity();
  command.stiffness_rotational = rotational * Eigen::Matrix3d::Identity();
  return command;
}

JointCommand jointStiffness(double first, double second) {
  JointCommand command = JointCommand::zero(2);
  command.fields = CommandField::kStiffness;
  command.stiffness = joints({first, second});
  return command;
}

void expectIn(const std::string& message, const std::vector<std::string>& fragments) {
  for (const std::string& fragment : fragments) {
    EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' in " << message;
  }
}

TEST(RateGainBound, ACartesianStiffnessIsHeldToTheLowestRateOverTheSwing) {
  // Rotation: 0.04 x (800 / 5)^2 = 1024 N m/rad; translation: 2.0 x 160^2 = 51200 N/m.
  EXPECT_TRUE(checkRenderable(stiffness(1000.0, 1020.0), rateBound(), kPeriod).accepted);
  const Verdict rotational = checkRenderable(stiffness(1000.0, 1030.0), rateBound(), kPeriod);
  EXPECT_FALSE(rotational.accepted);
  EXPECT_EQ(rotational.reason, RejectionReason::kInvalidGains);
  expectIn(rotational.message, {"stiffness_rotational 1.03e+03 N m/rad", "1.02e+03 N m/rad",
                                "0.04 kg m^2", "800 N m/s torque-rate limit", "5 N m swing"});
  EXPECT_TRUE(checkRenderable(stiffness(51000.0, 10.0), rateBound(), kPeriod).accepted);
  const Verdict translational = checkRenderable(stiffness(51400.0, 10.0), rateBound(), kPeriod);
  EXPECT_FALSE(translational.accepted);
  expectIn(translational.message, {"stiffness_translational", "5.12e+04 N/m"});
}

TEST(RateGainBound, AJointStiffnessIsHeldToItsOwnJointsRate) {
  // Joint 1: 0.3 x (1000 / 5)^2 = 12000; joint 2: 0.05 x (800 / 5)^2 = 1280 N m/rad.
  EXPECT_TRUE(checkRenderable(jointStiffness(11900.0, 1270.0), rateBound(), kPeriod).accepted);
  const Verdict first = checkRenderable(jointStiffness(12100.0, 10.0), rateBound(), kPeriod);
  EXPECT_FALSE(first.accepted);
  expectIn(first.message, {"stiffness of joint 1", "1.2e+04 N m/rad", "1e+03 N m/s"});
  const Verdict second = checkRenderable(jointStiffness(10.0, 1290.0), rateBound(), kPeriod);
  EXPECT_FALSE(second.accepted);
  expectIn(second.message, {"stiffness of joint 2", "1.28e+03 N m/rad", "800 N m/s"});
  // The nullspace springs too, each on its joint.
  CartesianCommand nullspace = stiffness(1000.0, 10.0);
  nullspace.fields = CommandField::kNullspace;
  nullspace.nullspace_stiffness = joints({10.0, 1290.0});
  nullspace.nullspace_damping = joints({0.0, 0.0});
  const Verdict held = checkRenderable(nullspace, rateBound(), kPeriod);
  EXPECT_FALSE(held.accepted);
  expectIn(held.message, {"nullspace_stiffness of joint 2"});
}

TEST(RateGainBound, TheSampledBoundGovernsWhereItIsTheLower) {
  // R / tau = 5000 / 5 = 1000 rad/s > c / T = 350 rad/s: 0.04 x 350^2 = 4900 N m/rad.
  GainBound bound = rateBound();
  bound.torque_rate_limit = joints({5000.0, 5000.0});
  EXPECT_TRUE(checkRenderable(stiffness(1000.0, 4890.0), bound, kPeriod).accepted);
  const Verdict verdict = checkRenderable(stiffness(1000.0, 4910.0), bound, kPeriod);
  EXPECT_FALSE(verdict.accepted);
  expectIn(verdict.message, {"4.9e+03 N m/rad", "(0.35 / 1 ms)^2"});
  EXPECT_EQ(verdict.message.find("torque-rate"), std::string::npos) << verdict.message;
}

TEST(RateGainBound, NoSwingOrNoRateLimitMeansNoRateBound) {
  GainBound no_swing = rateBound();
  no_swing.rate_limit_swing_nm = 0.0;
  EXPECT_TRUE(checkRenderable(stiffness(1000.0, 4890.0), no_swing, kPeriod).accepted);
  GainBound no_rate = rateBound();  // joint_pd, the admittance modes: no rate limit on the law
  no_rate.torque_rate_limit.resize(0);
  EXPECT_TRUE(checkRenderable(stiffness(1000.0, 4890.0), no_rate, kPeriod).accepted);
  EXPECT_FALSE(checkRenderable(stiffness(1000.0, 4910.0), no_rate, kPeriod).accepted);
}

// ---- the model behind the bound -------------------------------------------------------------

/// The header's loop on one inertia: from rest, a reference step whose spring torque is
/// `swing_nm`; returns how many of the last 0.5 s of periods the rate limit clipped (0: the swing
/// died out; a limit cycle clips nearly every period).
int clippedPeriodsAtTheEnd(double natural_frequency, double damping_ratio, double rate_nm_per_s,
                           double period_s, int delay_periods, double swing_nm) {
  const double inertia = 0.05;  // [kg m^2]; the result depends on w_n, zeta, R, T and tau only
  const double stiffness = inertia * natural_frequency * natural_frequency;
  const double damping = 2.0 * damping_ratio * std::sqrt(stiffness * inertia);
  double position = -swing_nm / stiffness;
  double velocity = 0.0;
  double torque = 0.0;
  std::deque<double> pending(static_cast<std::size_t>(delay_periods), 0.0);
  const int periods = static_cast<int>(std::lround(3.0 / period_s));
  const int tail = static_cast<int>(std::lround(0.5 / period_s));
  int clipped = 0;
  for (int k = 0; k < periods; ++k) {
    const double wanted = -stiffness * position - damping * velocity;
    const double step = rate_nm_per_s * period_s;
    if (std::abs(wanted - torque) > step && k >= periods - tail) {
      ++clipped;
    }
    torque += std::clamp(wanted - torque, -step, step);
    pending.push_back(torque);
    const double applied = pending.front();
    pending.pop_front();
    position += period_s * velocity + 0.5 * period_s * period_s * applied / inertia;
    velocity += period_s * applied / inertia;
  }
  return clipped;
}

TEST(RateGainBoundModel, AtTheBoundASwingOfTauDiesOutForEveryDampingAndDelay) {
  // w_n T = 0.2 at 1 kHz: damping ratios up to 1.5 keep zeta w_n T inside the sampled bound.
  const double rate = 1000.0;
  for (const double zeta : {0.2, 0.5, 0.7, 1.0, 1.5}) {
    for (const int delay : {0, 1}) {
      EXPECT_EQ(clippedPeriodsAtTheEnd(rate / kSwingNm, zeta, rate, kPeriod, delay, kSwingNm), 0)
          << "zeta " << zeta << ", delay " << delay;
    }
  }
}

TEST(RateGainBoundModel, ASwingAboveKappaRTOverWnStartsTheLimitCycle) {
  // The header's kappa at zeta = 1 without the extra delay, w_n T = 0.1: 3.5 (describing
  // function and this loop agree). A swing of 3 R / w_n dies out, one of 4 R / w_n does not.
  const double rate = 1000.0;
  const double natural_frequency = 100.0;
  EXPECT_EQ(clippedPeriodsAtTheEnd(natural_frequency, 1.0, rate, kPeriod, 0,
                                   3.0 * rate / natural_frequency),
            0);
  EXPECT_GT(clippedPeriodsAtTheEnd(natural_frequency, 1.0, rate, kPeriod, 0,
                                   4.0 * rate / natural_frequency),
            400);
  // Three times the bound's w_n (at 4 kHz, inside the sampled bound), a swing of 6 tau: the
  // limit cycle, with or without a period of delay.
  for (const int delay : {0, 1}) {
    EXPECT_GT(
        clippedPeriodsAtTheEnd(3.0 * rate / kSwingNm, 1.0, rate, 0.25e-3, delay, 6.0 * kSwingNm),
        1600)
        << "delay " << delay;
  }
}

}  // namespace
}  // namespace comply::pipeline::test
