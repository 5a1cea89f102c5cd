// Gains the arm renders stably (pipeline/gain_bound.hpp), on the four robots. The bound comes
// from the arm's lightest inertia over the workspace and the control period: a command above it
// is refused with the numbers, one just below is taken, and a step at the bound on the arm at
// home settles without a fault. The sampled loop's bound alone here (the torque-rate part off;
// rate_limit_bound_test.cpp has that part). Before, 1e6 N/m was taken on every robot and the arm
// saturated (the stability guard's FAULT was all that stopped it).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

constexpr double kPeriod = 0.001;

class GainBoundOn : public ::testing::TestWithParam<std::string> {};

/// config/sim/cartesian_impedance.yaml on `robot`, the gain bound's torque-rate part off.
pipeline::WrapperConfig sampledBoundOnly(const std::string& robot) {
  pipeline::WrapperConfig config = simCartesianConfig(robot);
  config.validation.rate_limit_swing_nm = 0.0;
  return config;
}

/// The stiffness bound along translation at 1 kHz [N/m].
double translationalBound(const pipeline::GainBound& bound) {
  return bound.translational_mass_kg * std::pow(bound.max_wn_period / kPeriod, 2);
}

TEST_P(GainBoundOn, TheLightestInertiasArePlausible) {
  const auto resolved = pipeline::resolveController(simCartesianConfig(GetParam()));
  const pipeline::GainBound& bound = resolved->gain_bound;
  ASSERT_TRUE(bound.enabled());
  // An arm of a few kg to 30 kg, its rotors included: the TCP weighs somewhere between a tenth of
  // a kilogram and its whole mass, a joint at least its rotor.
  EXPECT_GT(bound.translational_mass_kg, 0.1);
  EXPECT_LT(bound.translational_mass_kg, 30.0);
  EXPECT_GT(bound.rotational_inertia_kg_m2, 1e-4);
  EXPECT_LT(bound.rotational_inertia_kg_m2, 1.0);
  const auto& armature = resolved->robot.joint_dynamics->armature;
  for (Eigen::Index i = 0; i < bound.joint_inertia.size(); ++i) {
    EXPECT_GE(bound.joint_inertia[i], armature[static_cast<std::size_t>(i)] - 1e-12) << i;
  }
  std::printf(
      "%s: lightest TCP mass %.3f kg, rotational inertia %.4f kg m^2 -> at 1 kHz "
      "%.3g N/m, %.3g N m/rad; joints",
      GetParam().c_str(), bound.translational_mass_kg, bound.rotational_inertia_kg_m2,
      translationalBound(bound),
      bound.rotational_inertia_kg_m2 * std::pow(bound.max_wn_period / kPeriod, 2));
  for (Eigen::Index i = 0; i < bound.joint_inertia.size(); ++i) {
    std::printf(" %.3g", bound.joint_inertia[i] * std::pow(bound.max_wn_period / kPeriod, 2));
  }
  std::printf(" N m/rad\n");
}

/// A wrapper on the simulated arm at home, active.
struct Rig {
  explicit Rig(pipeline::WrapperConfig config)
      : plant(*config.robot_description, sim::PlantOptions{}), wrapper(std::move(config)) {
    state = JointState::zero(wrapper.dof());
    plant.read(state);
    wrapper.activate(state);
  }
  CartesianCommand stiffness(double stiffness_n_per_m, double step_m = 0.0) {
    CartesianCommand command = CartesianCommand::zero(wrapper.dof());
    command.stamp_s = ++stamp_s;
    command.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping;
    command.position = wrapper.measuredPose().tcp_position + Eigen::Vector3d(step_m, 0.0, 0.0);
    command.orientation = wrapper.measuredPose().tcp_orientation;
    command.stiffness_translational = stiffness_n_per_m * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 50.0 * Eigen::Matrix3d::Identity();
    command.damping_mode = DampingMode::kRatio;
    command.damping_ratio.setOnes();
    return command;
  }
  void cycle() {
    JointVector torque = JointVector::Zero(wrapper.dof());
    plant.read(state);
    wrapper.update(state, kPeriod, {torque.data(), static_cast<std::size_t>(wrapper.dof())});
    plant.write({torque.data(), static_cast<std::size_t>(wrapper.dof())});
    plant.step();
  }

  sim::SimulatedRobot plant;
  pipeline::CartesianWrapper wrapper;
  JointState state;
  double stamp_s = 0.0;
};

TEST_P(GainBoundOn, AStiffnessAboveTheBoundIsRefusedWithItsNumbers) {
  Rig rig(sampledBoundOnly(GetParam()));
  rig.cycle();  // the period is known from the first cycle on
  const double bound = translationalBound(rig.wrapper.controller().resolved().gain_bound);
  const pipeline::Verdict above = rig.wrapper.submit(rig.stiffness(1.01 * bound));
  EXPECT_FALSE(above.accepted);
  EXPECT_EQ(above.reason, pipeline::RejectionReason::kInvalidGains);
  EXPECT_NE(above.message.find("stiffness_translational"), std::string::npos) << above.message;
  EXPECT_NE(above.message.find("renders stably"), std::string::npos) << above.message;
  EXPECT_NE(above.message.find(GetParam()), std::string::npos) << above.message;
  EXPECT_TRUE(rig.wrapper.submit(rig.stiffness(0.99 * bound)).accepted);
  // The red team's gains: 1e6 N/m is above every robot's bound.
  EXPECT_FALSE(rig.wrapper.submit(rig.stiffness(1e6, 0.05)).accepted);
  // So is a damping ratio that the stiffness at the bound cannot carry.
  CartesianCommand heavily_damped = rig.stiffness(0.99 * bound);
  heavily_damped.damping_ratio.setConstant(2.0);
  EXPECT_FALSE(rig.wrapper.submit(heavily_damped).accepted);
}

TEST_P(GainBoundOn, ARatioIsCheckedWithTheStiffnessItActsWith) {
  Rig rig(sampledBoundOnly(GetParam()));
  rig.cycle();
  const double bound = translationalBound(rig.wrapper.controller().resolved().gain_bound);
  ASSERT_TRUE(rig.wrapper.submit(rig.stiffness(0.25 * bound)).accepted);
  // A damping ratio sent alone meets the stiffness in force: zeta sqrt(K/m) T = 10 x 0.175.
  CartesianCommand ratio_alone = CartesianCommand::zero(rig.wrapper.dof());
  ratio_alone.stamp_s = ++rig.stamp_s;
  ratio_alone.fields = CommandField::kDamping;
  ratio_alone.damping_mode = DampingMode::kRatio;
  ratio_alone.damping_ratio.setConstant(10.0);
  const pipeline::Verdict refused = rig.wrapper.submit(ratio_alone);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.message.find("damping_ratio"), std::string::npos) << refused.message;
  ratio_alone.damping_ratio.setConstant(1.5);  // 1.5 x 0.175 = 0.26: renderable
  EXPECT_TRUE(rig.wrapper.submit(ratio_alone).accepted);
  // And a stiffness sent alone meets the ratio in force: at the bound, a ratio of 1.5 is too much.
  CartesianCommand stiffness_alone = rig.stiffness(0.99 * bound);
  stiffness_alone.fields = CommandField::kStiffness;
  EXPECT_FALSE(rig.wrapper.submit(stiffness_alone).accepted);
}

TEST_P(GainBoundOn, AConfigurationsInitialStiffnessAboveTheBoundIsRefused) {
  pipeline::WrapperConfig config = simCartesianConfig(GetParam());
  config.initial_cartesian.stiffness_translational = 1e6 * Eigen::Matrix3d::Identity();
  try {
    (void)pipeline::resolveController(config);
    FAIL() << "1e6 N/m was taken as the initial stiffness";
  } catch (const comply::InputError& error) {
    EXPECT_EQ(error.key(), "initial");
    EXPECT_NE(std::string(error.what()).find("renders stably"), std::string::npos) << error.what();
  }
  config.validation.max_wn_period = 0.0;  // the bound off: taken (the guard is then what is left)
  EXPECT_NO_THROW((void)pipeline::resolveController(config));
}

TEST_P(GainBoundOn, AStepAtTheBoundSettles) {
  Rig rig(sampledBoundOnly(GetParam()));
  rig.cycle();
  const double stiffness =
      0.99 * translationalBound(rig.wrapper.controller().resolved().gain_bound);
  // A step that asks for 10 N: the gain, not the effort limit, is what is tested.
  const double step_m = 10.0 / stiffness;
  const Eigen::Vector3d start = rig.wrapper.measuredPose().tcp_position;
  ASSERT_TRUE(rig.wrapper.submit(rig.stiffness(stiffness, step_m)).accepted);
  double late_error_m = 0.0;
  for (int cycle = 0; cycle < 1500; ++cycle) {
    rig.cycle();
    if (cycle >= 1000) {
      const Eigen::Vector3d at = rig.wrapper.measuredPose().tcp_position;
      late_error_m = std::max(late_error_m, std::abs(at.x() - start.x() - step_m));
    }
  }
  EXPECT_EQ(rig.wrapper.diagnostics().state, pipeline::WrapperState::kActive)
      << rig.wrapper.diagnostics().last_fault;
  EXPECT_EQ(rig.wrapper.diagnostics().effort_limit_hits, 0U);
  // Settled: within a third of the step (gravity and friction leave a small offset), no ringing.
  EXPECT_LT(late_error_m, step_m / 3.0) << "step " << step_m * 1e3 << " mm";
}

INSTANTIATE_TEST_SUITE_P(FourRobots, GainBoundOn,
                         ::testing::Values("fr3", "iiwa14", "rizon4s", "ur5e"));

}  // namespace
}  // namespace comply::testing
