// Gains bounded in every output mode, and the nullspace target's jump limited, on the four robots
// (issue 46, findings 6 and 7). Before, output.mode joint_pd took 1e6 N/m (only torque output was
// bounded) and drove the joints past their speed limit into a FAULT; and a nullspace target
// 1.5 rad away was taken (no jump limit), reaching 1.03-1.08x the joint speed limit.
//   joint_pd            the torque mode's bound, and the drives' kp_i = J_i^T K J_i, kd_i at the
//                       cycle's period on each joint's lightest inertia;
//   position, velocity  the bound on the virtual arm's inertia (the arm's plus the added), along
//                       translation only (the virtual arm carries no rotor inertias).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "output_modes/output_mode_rig.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

using experiments::kRigPeriodS;
using experiments::outputModeConfig;
using experiments::OutputModeRig;
using experiments::plantOf;

class OutputModeBoundOn : public ::testing::TestWithParam<std::string> {};

double square(double x) {
  return x * x;
}

/// The largest translational stiffness the bound takes at 1 kHz [N/m]: the Cartesian bound and,
/// with drive gains, each joint's kp_i = k |J_i,linear|^2 at the rotational stiffness `k_r`.
double translationalBound(const pipeline::GainBound& bound, double k_r) {
  const double rate = square(bound.max_wn_period / kRigPeriodS);
  double limit = bound.translational_mass_kg * rate;
  for (Eigen::Index i = 0; bound.drive_gains && i < bound.joint_inertia.size(); ++i) {
    const double room = bound.joint_inertia[i] * rate - k_r * bound.joint_axis_sq[i];
    if (bound.joint_lever_sq[i] > 0.0) {
      limit = std::min(limit, room / bound.joint_lever_sq[i]);
    }
  }
  return limit;
}

CartesianCommand stiffness(const pipeline::CartesianWrapper& wrapper, double translational,
                           double stamp_s) {
  CartesianCommand command = CartesianCommand::zero(wrapper.dof());
  command.stamp_s = stamp_s;
  command.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping;
  command.position = wrapper.measuredPose().tcp_position;
  command.orientation = wrapper.measuredPose().tcp_orientation;
  command.stiffness_translational = translational * Eigen::Matrix3d::Identity();
  command.stiffness_rotational = 50.0 * Eigen::Matrix3d::Identity();
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setOnes();
  return command;
}

void expectInitialRefused(pipeline::WrapperConfig config, const std::string& fragment) {
  config.initial_cartesian.stiffness_translational = 1e6 * Eigen::Matrix3d::Identity();
  try {
    (void)pipeline::resolveController(config);
    ADD_FAILURE() << "1e6 N/m was taken as the initial stiffness in " << fragment;
  } catch (const comply::InputError& error) {
    const std::string what = error.what();
    EXPECT_EQ(error.key(), "initial");
    EXPECT_NE(what.find("renders stably"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    std::printf("%s\n", what.c_str());
  }
}

TEST_P(OutputModeBoundOn, JointPdRefusesTheRedTeamsStiffnessWithItsNumbers) {
  const pipeline::WrapperConfig config = outputModeConfig(GetParam(), OutputMode::kJointPd);
  expectInitialRefused(config, "output.mode joint_pd");
  OutputModeRig<> rig(config, plantOf(OutputMode::kJointPd));
  ASSERT_TRUE(rig.cycle());  // the period is known from the first cycle on
  const pipeline::GainBound& bound = rig.wrapper.controller().resolved().gain_bound;
  ASSERT_TRUE(bound.drive_gains);
  const pipeline::Verdict refused = rig.wrapper.submit(stiffness(rig.wrapper, 1e6, 1.0));
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.reason, pipeline::RejectionReason::kInvalidGains);
  EXPECT_NE(refused.message.find("renders stably"), std::string::npos) << refused.message;
  EXPECT_NE(refused.message.find(GetParam()), std::string::npos) << refused.message;
  std::printf("%s joint_pd, 1e6 N/m: %s\n", GetParam().c_str(), refused.message.c_str());
  // Just below the bound (the Cartesian one or a drive's, whichever is lower) is taken, and the
  // arm holds it without a fault; just above is refused.
  const double limit = translationalBound(bound, 50.0);
  std::printf("%s joint_pd: translational stiffness bound %.4g N/m (torque mode's %.4g N/m)\n",
              GetParam().c_str(), limit,
              bound.translational_mass_kg * square(bound.max_wn_period / kRigPeriodS));
  EXPECT_FALSE(rig.wrapper.submit(stiffness(rig.wrapper, 1.01 * limit, 2.0)).accepted);
  ASSERT_TRUE(rig.wrapper.submit(stiffness(rig.wrapper, 0.99 * limit, 3.0)).accepted);
  for (int cycle = 0; cycle < 500; ++cycle) {
    ASSERT_TRUE(rig.cycle()) << "cycle " << cycle << ": " << rig.wrapper.diagnostics().last_fault;
  }
}

TEST_P(OutputModeBoundOn, AdmittanceBoundsTheVirtualArmAlongTranslation) {
  for (const OutputMode mode : {OutputMode::kPosition, OutputMode::kVelocity}) {
    pipeline::WrapperConfig config = outputModeConfig(GetParam(), mode);
    expectInitialRefused(config, "virtual arm");
    const auto plain = pipeline::resolveController(config);
    config.output.admittance.added_mass_kg.setConstant(5.0);
    const auto added = pipeline::resolveController(config);
    const pipeline::GainBound& bound = added->gain_bound;
    ASSERT_TRUE(bound.enabled());
    EXPECT_FALSE(bound.drive_gains);
    // The added mass makes the virtual arm heavier, so stiffer gains are taken.
    EXPECT_GT(bound.translational_mass_kg, plain->gain_bound.translational_mass_kg + 1.0);
    // Rotation and the joints are not bounded: the virtual arm has no rotor inertias, and its
    // bare wrist would refuse the default 300 N m/rad (printed below).
    EXPECT_TRUE(std::isinf(bound.rotational_inertia_kg_m2));
    EXPECT_TRUE(std::isinf(bound.joint_inertia.maxCoeff()));
    const pipeline::GainBound bare = pipeline::lightestInertias(*plain->model, {});
    const double rate = square(bound.max_wn_period / kRigPeriodS);
    std::printf(
        "%s %s: virtual arm's lightest TCP mass %.3f kg (%.3f with 5 kg added) -> %.4g "
        "N/m at 1 kHz; its bare rotational inertia %.3g kg m^2 would bound rotation at "
        "%.3g N m/rad\n",
        GetParam().c_str(), std::string(toString(mode)).c_str(),
        plain->gain_bound.translational_mass_kg, bound.translational_mass_kg,
        plain->gain_bound.translational_mass_kg * rate, bare.rotational_inertia_kg_m2,
        bare.rotational_inertia_kg_m2 * rate);
    OutputModeRig<> rig(outputModeConfig(GetParam(), mode), plantOf(mode));
    ASSERT_TRUE(rig.cycle());
    const pipeline::Verdict refused = rig.wrapper.submit(stiffness(rig.wrapper, 1e6, 1.0));
    EXPECT_EQ(refused.reason, pipeline::RejectionReason::kInvalidGains) << refused.message;
    EXPECT_NE(refused.message.find("virtual arm"), std::string::npos) << refused.message;
    EXPECT_FALSE(refused.accepted);
    const double limit = plain->gain_bound.translational_mass_kg * rate;
    EXPECT_FALSE(rig.wrapper.submit(stiffness(rig.wrapper, 1.01 * limit, 2.0)).accepted);
    EXPECT_TRUE(rig.wrapper.submit(stiffness(rig.wrapper, 0.99 * limit, 3.0)).accepted);
  }
}

/// A nullspace target `offset_rad` from the measured joints on the first joint.
CartesianCommand nullspaceJump(const pipeline::CartesianWrapper& wrapper, double offset_rad,
                               double stamp_s) {
  CartesianCommand command = CartesianCommand::zero(wrapper.dof());
  command.stamp_s = stamp_s;
  command.fields = CommandField::kNullspace;
  command.nullspace_position = wrapper.measuredPose().position;
  command.nullspace_position[0] += offset_rad;
  command.nullspace_stiffness.setConstant(wrapper.dof(), 5.0);
  command.nullspace_damping.setConstant(wrapper.dof(), 0.5);
  return command;
}

TEST_P(OutputModeBoundOn, ANullspaceJumpBeyondTheLimitIsRefused) {
  OutputModeRig<> rig(outputModeConfig(GetParam(), OutputMode::kTorque),
                      plantOf(OutputMode::kTorque));
  ASSERT_TRUE(rig.cycle());
  for (const double jump : {1.5, -1.5}) {
    const pipeline::Verdict refused = rig.wrapper.submit(nullspaceJump(rig.wrapper, jump, 1.0));
    EXPECT_FALSE(refused.accepted);
    EXPECT_EQ(refused.reason, pipeline::RejectionReason::kPoseJump) << refused.message;
    EXPECT_NE(refused.message.find("nullspace_position is 1.5 rad"), std::string::npos)
        << refused.message;
  }
  ASSERT_TRUE(rig.wrapper.submit(nullspaceJump(rig.wrapper, 0.3, 2.0)).accepted);
  for (int cycle = 0; cycle < 500; ++cycle) {
    ASSERT_TRUE(rig.cycle()) << "cycle " << cycle << ": " << rig.wrapper.diagnostics().last_fault;
  }
}

INSTANTIATE_TEST_SUITE_P(FourRobots, OutputModeBoundOn,
                         ::testing::Values("fr3", "iiwa14", "rizon4s", "ur5e"));

}  // namespace
}  // namespace comply::testing
