// The gain bound's check of a joint_pd drive's own gains (pipeline/gain_bound.hpp): a Cartesian
// law's stiffness K reaches joint i's drive as kp_i = J_i^T K J_i, at most k_t |J_i,linear|^2 +
// k_r |J_i,angular|^2 over the workspace; each is held to joint i's lightest inertia at the
// period, w_n T <= c. Hand numbers on a two-joint bound: inertias 0.5 and 0.02 kg m^2, levers
// 0.8 m and 0.1 m, c = 0.35, T = 1 ms: kp_1 <= 0.5 x 350^2 = 61250 N m/rad.

#include <gtest/gtest.h>

#include <string>

#include "command_bits.hpp"
#include "comply/pipeline/gain_bound.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kPeriod = 1e-3;

GainBound twoJoints(bool drive_gains) {
  GainBound bound;
  bound.translational_mass_kg = 100.0;  // the Cartesian check out of the way
  bound.rotational_inertia_kg_m2 = 100.0;
  bound.joint_inertia = joints({0.5, 0.02});
  bound.joint_lever_sq = joints({0.64, 0.01});
  bound.joint_axis_sq = joints({1.0, 1.0});
  bound.drive_gains = drive_gains;
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

TEST(DriveGainBound, AStiffnessWhoseDriveGainIsAboveTheBoundIsRefused) {
  // Joint 1: 0.64 k_t + k_r <= 61250; with k_r = 250, k_t <= 95312.5 N/m.
  const Verdict above = checkRenderable(stiffness(95400.0, 250.0), twoJoints(true), kPeriod);
  EXPECT_FALSE(above.accepted);
  EXPECT_EQ(above.reason, RejectionReason::kInvalidGains);
  for (const char* fragment : {"joint_pd drive kp of joint 1", "6.13e+04 N m/rad", "two-joint"}) {
    EXPECT_NE(above.message.find(fragment), std::string::npos) << above.message;
  }
  EXPECT_TRUE(checkRenderable(stiffness(95200.0, 250.0), twoJoints(true), kPeriod).accepted);
  // Joint 2's bound, 0.02 x 350^2 = 2450 N m/rad, holds the rotational stiffness.
  const Verdict rotational = checkRenderable(stiffness(0.0, 2500.0), twoJoints(true), kPeriod);
  EXPECT_FALSE(rotational.accepted);
  EXPECT_NE(rotational.message.find("joint 2"), std::string::npos) << rotational.message;
}

TEST(DriveGainBound, OnlyJointPdWithACartesianLawChecksTheDrives) {
  EXPECT_TRUE(checkRenderable(stiffness(95400.0, 250.0), twoJoints(false), kPeriod).accepted);
}

TEST(DriveGainBound, TheDrivesDampingIsBoundedToo) {
  CartesianCommand command = stiffness(1000.0, 10.0);
  command.fields = CommandField::kDamping;
  command.damping_mode = DampingMode::kAbsolute;
  // Joint 1: kd <= 2 x 0.35 x 0.5 / 1 ms = 350 N m s/rad; 0.64 d_t + d_r <= 350.
  command.damping_translational = 540.0 * Eigen::Matrix3d::Identity();
  command.damping_rotational.setZero();
  EXPECT_TRUE(checkRenderable(command, twoJoints(true), kPeriod).accepted);
  command.damping_translational = 550.0 * Eigen::Matrix3d::Identity();
  command.damping_rotational = 3.0 * Eigen::Matrix3d::Identity();
  const Verdict verdict = checkRenderable(command, twoJoints(true), kPeriod);
  EXPECT_FALSE(verdict.accepted);
  EXPECT_NE(verdict.message.find("joint_pd drive kd of joint 1"), std::string::npos)
      << verdict.message;
  // A damping ratio on the drive's kp: joint 1 at kp = 0.64 x 60000 = 38400 N m/rad,
  // zeta sqrt(38400 / 0.5) 1 ms <= 0.35 holds zeta <= 1.26 (the mean of the six).
  command = stiffness(60000.0, 0.0);
  command.fields = CommandField::kStiffness | CommandField::kDamping;
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setConstant(1.2);
  EXPECT_TRUE(checkRenderable(command, twoJoints(true), kPeriod).accepted);
  command.damping_ratio.setConstant(1.3);
  EXPECT_FALSE(checkRenderable(command, twoJoints(true), kPeriod).accepted);
}

}  // namespace
}  // namespace comply::pipeline::test
