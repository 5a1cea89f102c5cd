// The contact-speed stage on the FR3's model (contact_speed.hpp): what resolving compiles from
// contact_speed.* and the body region, the reflected mass with the rotors' inertia, and what the
// stage does to a torque below, within and past its limit. On the simulated plant, against
// MuJoCo's own inertia and into a spring: tests/sim/contact_speed_test.cpp.

#include "comply/pipeline/contact_speed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline {
namespace {

using namespace test;

constexpr double kPeriodS = 0.001;

/// The FR3 at rest at home under `lines`, activated (its model data computed there).
struct HomeFr3 {
  explicit HomeFr3(const std::string& lines)
      : controller(resolveController(fr3Config(kCartesianImpedancePlugin, lines))) {
    controller.activate(restingAt(controller, fr3Home()));
  }
  [[nodiscard]] const model::Data& data() const { return controller.modelData(); }
  [[nodiscard]] const CycleParameters& parameters() const {
    return controller.resolved().parameters;
  }
  Controller controller;
};

/// A joint velocity that moves the TCP at `velocity` [m/s] (and turns it not at all).
JointVector jointVelocityFor(const model::Data& data, const Eigen::Vector3d& velocity) {
  const Eigen::MatrixXd jacobian = data.jacobian.leftCols(kFr3Dof);
  Vector6d twist = Vector6d::Zero();
  twist.head<3>() = velocity;
  return jacobian.transpose() * (jacobian * jacobian.transpose()).ldlt().solve(twist);
}

/// The TCP force F with J_v^T F the share of `torque` that is one (least squares).
Eigen::Vector3d forceOf(const model::Data& data, const JointVector& torque) {
  const Eigen::MatrixXd linear = data.jacobian.topLeftCorner(3, kFr3Dof);
  return (linear * linear.transpose()).ldlt().solve(linear * torque.head(kFr3Dof));
}

void expectResolveError(const std::string& plugin, const std::string& lines,
                        const std::string& fragment) {
  try {
    (void)resolveController(fr3Config(plugin, lines));
    ADD_FAILURE() << "resolved:\n" << lines;
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

const std::string kOn = "contact_speed:\n  enabled: true\n";

TEST(ContactSpeed, CompilesTheRegionsRowTheOverridesThePayloadAndTheRotorInertias) {
  HomeFr3 hands(kOn);
  const ContactSpeedParameters& compiled = hands.parameters().contact_speed;
  EXPECT_TRUE(compiled.enabled);
  EXPECT_EQ(compiled.force_limit_n, 140.0);  // hands, quasi-static
  EXPECT_EQ(compiled.stiffness_n_per_m, 75e3);
  EXPECT_EQ(compiled.body_mass_kg, 0.0) << "clamped by default";
  EXPECT_EQ(compiled.payload_mass_kg, 0.0);
  // The rotors are in the laws' M (ModelOptions::armature), which the stage reads.
  const std::vector<double> armature = hands.controller.resolved().robot.joint_dynamics->armature;
  EXPECT_EQ(hands.controller.model().armature(), armature);
  HomeFr3 chest(kOn +
                "  body_region: chest\n  contact: transient\n  body_mass: true\n"
                "compensation:\n  payload:\n    mass_kg: 1.5\n");
  EXPECT_EQ(chest.parameters().contact_speed.force_limit_n, 280.0);
  EXPECT_EQ(chest.parameters().contact_speed.stiffness_n_per_m, 25e3);
  EXPECT_EQ(chest.parameters().contact_speed.body_mass_kg, 40.0);
  EXPECT_EQ(chest.parameters().contact_speed.payload_mass_kg, 1.5);
  HomeFr3 set(kOn + "  force_limit_n: 90\n  stiffness_n_per_m: 20000\n");
  EXPECT_EQ(set.parameters().contact_speed.force_limit_n, 90.0);
  EXPECT_EQ(set.parameters().contact_speed.stiffness_n_per_m, 20e3);
  EXPECT_FALSE(HomeFr3("").parameters().contact_speed.enabled);
}

TEST(ContactSpeed, ResolvingRefusesAJointLawAndTheAdmittanceModes) {
  expectResolveError(kJointImpedancePlugin, kOn, "needs a Cartesian law");
  expectResolveError(kCartesianImpedancePlugin, kOn + "output:\n  mode: position\n",
                     "output.mode position");
  expectResolveError(kCartesianImpedancePlugin, kOn + "output:\n  mode: velocity\n",
                     "output.mode velocity");
}

TEST(ContactSpeed, TheReflectedMassCountsTheRotorsInertia) {
  HomeFr3 arm(kOn);
  const model::Data& data = arm.data();
  ReflectedInertia inertia;
  ASSERT_TRUE(inertia.factorise(data, JointVector(), kFr3Dof));  // as the stage does
  // The model's M carries the rotors on its diagonal; without them, the links' alone.
  const std::vector<double>& rotors = arm.controller.model().armature();
  ASSERT_EQ(rotors.size(), static_cast<std::size_t>(kFr3Dof));
  Eigen::MatrixXd links = data.mass_matrix.topLeftCorner(kFr3Dof, kFr3Dof);
  for (int i = 0; i < kFr3Dof; ++i) {
    links(i, i) -= rotors[static_cast<std::size_t>(i)];
  }
  const std::vector<Eigen::Vector3d> directions = {
      Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.0, 0.6, -0.8)};
  for (const Eigen::Vector3d& u : directions) {
    const double with_rotors = inertia.mass(data, u);
    // Dense, the textbook way: (u^T J_v M^-1 J_v^T u)^-1.
    const Eigen::MatrixXd m = data.mass_matrix.topLeftCorner(kFr3Dof, kFr3Dof);
    const Eigen::MatrixXd jv = data.jacobian.topLeftCorner(3, kFr3Dof);
    const double expected = 1.0 / (u.transpose() * jv * m.inverse() * jv.transpose() * u)(0);
    EXPECT_NEAR(with_rotors, expected, 1e-9 * expected) << u.transpose();
    // A torque J_v^T F accelerates the TCP along u by u . F / mass.
    const JointVector pushed = jv.transpose() * (2.0 * u);
    EXPECT_NEAR(inertia.accelerationAlong(pushed), 2.0 / with_rotors, 1e-12);
    const double links_only = 1.0 / (u.transpose() * jv * links.inverse() * jv.transpose() * u)(0);
    EXPECT_GT(with_rotors, 1.2 * links_only) << u.transpose() << ": the rotors are heavy";
  }
}

TEST(ContactSpeed, TheReflectedMassMatchesADenseInverseForEveryJointCount) {
  // The factorisation's loops are unrolled for 6 and 7 joints and run to `dof` otherwise; each
  // path against the textbook inverse, the rotors' list added to M's diagonal.
  HomeFr3 arm(kOn);
  model::Data data = arm.data();
  std::srand(7);
  for (const int dof : {2, 6, 7, 9, kMaxDof}) {
    const Eigen::MatrixXd root = Eigen::MatrixXd::Random(dof, dof);
    const Eigen::MatrixXd m = root * root.transpose() + 0.1 * Eigen::MatrixXd::Identity(dof, dof);
    data.mass_matrix = m;
    data.jacobian = Eigen::MatrixXd::Random(6, dof);
    const JointVector rotors = JointVector::Constant(dof, 0.25);
    ReflectedInertia inertia;
    ASSERT_TRUE(inertia.factorise(data, rotors, dof)) << dof;
    Eigen::MatrixXd with_rotors = m;
    with_rotors.diagonal().array() += 0.25;
    const Eigen::MatrixXd inverse = with_rotors.inverse();
    const Eigen::MatrixXd jv = data.jacobian.topLeftCorner(3, dof);
    const Eigen::Vector3d u = Eigen::Vector3d(0.3, -0.5, 0.81).normalized();
    const double expected = 1.0 / (u.transpose() * jv * inverse * jv.transpose() * u)(0);
    EXPECT_NEAR(inertia.mass(data, u), expected, 1e-9 * expected) << dof;
    const JointVector torque = Eigen::VectorXd::LinSpaced(dof, -2.0, 3.0);
    const double along = (u.transpose() * jv * inverse * torque)(0);
    EXPECT_NEAR(inertia.accelerationAlong(torque), along, 1e-9 * (1.0 + std::abs(along))) << dof;
    // Not positive definite: no factor, an infinite mass, no acceleration.
    data.mass_matrix(dof - 1, dof - 1) = -1.0;
    EXPECT_FALSE(inertia.factorise(data, JointVector(), dof)) << dof;
    EXPECT_TRUE(std::isinf(inertia.mass(data, u))) << dof;
    EXPECT_EQ(inertia.accelerationAlong(torque), 0.0) << dof;
  }
}

TEST(ContactSpeed, LeavesSlowMotionBitForBitScalesAPushTowardTheContactAndBrakesPastIt) {
  HomeFr3 arm(kOn + "compensation:\n  payload:\n    mass_kg: 0.5\n");
  const model::Data& data = arm.data();
  const CycleParameters& parameters = arm.parameters();
  ContactSpeed stage(parameters, kFr3Dof, /*cartesian=*/true);
  ASSERT_TRUE(stage.enabled());
  const Eigen::Vector3d u(0.0, 0.6, -0.8);
  const double arm_kg = reflectedMass(data, JointVector(), kFr3Dof, u);
  const double v_max = 140.0 / std::sqrt((arm_kg + 0.5) * 75e3);
  const JointVector compensation = JointVector::Constant(kFr3Dof, 3.0);
  // A law torque pushing the TCP along u (J_v^T u: positive acceleration along u).
  const JointVector push = 20.0 * data.jacobian.topLeftCorner(3, kFr3Dof).transpose() * u;
  const auto run = [&](double speed, const JointVector& law_in, JointVector& law,
                       JointVector& torque) {
    Vector6d twist = Vector6d::Zero();
    twist.head<3>() = speed * u;
    law = law_in;
    torque = compensation + law;
    return stage.apply(data, twist, kPeriodS, law, torque);
  };
  JointVector law;
  JointVector torque;

  // Below half the limit: nothing changes, bit for bit, however hard the law pushes.
  EXPECT_FALSE(run(0.45 * v_max, 10.0 * push, law, torque));
  EXPECT_EQ(torque, compensation + 10.0 * push);
  EXPECT_NEAR(stage.limit(), v_max, 1e-12);
  EXPECT_NEAR(stage.mass(), arm_kg + 0.5, 1e-12);
  EXPECT_EQ(stage.share(), 1.0);

  // At 0.7 v_max: the push scaled to (0.85 - 0.7) / 0.35, the compensation untouched.
  EXPECT_TRUE(run(0.7 * v_max, push, law, torque));
  EXPECT_NEAR(stage.share(), 0.15 / 0.35, 1e-9);
  COMPLY_EXPECT_JOINTS_NEAR(law, stage.share() * push, 1e-12);
  COMPLY_EXPECT_JOINTS_NEAR(torque, compensation + law, 1e-12);
  EXPECT_EQ(stage.brakeForce(), 0.0);
  // A law braking along u is never scaled.
  EXPECT_FALSE(run(0.7 * v_max, -push, law, torque));
  EXPECT_EQ(torque, compensation - push);

  // Past 0.85 v_max: no push, and a brake along -u, half of deadbeat on the mass along u.
  EXPECT_TRUE(run(0.95 * v_max, push, law, torque));
  EXPECT_EQ(stage.share(), 0.0);
  EXPECT_EQ(law, JointVector::Zero(kFr3Dof));
  const double expected_brake = (arm_kg + 0.5) / (2.0 * kPeriodS) * 0.10 * v_max;
  EXPECT_NEAR(stage.brakeForce(), expected_brake, 1e-9 * expected_brake);
  const Eigen::Vector3d force = forceOf(data, torque - compensation);
  EXPECT_NEAR(force.dot(u), -expected_brake, 1e-6 * expected_brake);
  EXPECT_NEAR((force - force.dot(u) * u).norm(), 0.0, 1e-6 * expected_brake) << "only along -u";
  const JointVector velocity = jointVelocityFor(data, 0.95 * v_max * u);
  EXPECT_LT(velocity.dot(torque - compensation), 0.0) << "the brake takes energy out";

  // Slower than 1 mm/s the direction is noise: nothing is computed, the last limit stays.
  EXPECT_FALSE(run(5e-4, push, law, torque));
  EXPECT_EQ(torque, compensation + push);
  EXPECT_NEAR(stage.limit(), v_max, 1e-12);
  stage.reset();
  EXPECT_EQ(stage.limit(), 0.0);
}

TEST(ContactSpeed, AFaultsHoldShowsNothingScaledOrBrakedAndTheLastLimit) {
  // 20 N into the hands' 75 N/mm: v_max about 4 cm/s, which the replayed motion passes.
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kOn + "  force_limit_n: 20\n"));
  const JointVector home = fr3Home();
  wrapper.activate(movingState(home, 0, 0.05, 0.5));
  TorqueBuffer torque;
  const ContactSpeed& stage = wrapper.controller().contactSpeed();
  bool braked = false;
  for (int cycle = 1; cycle <= 500 && !braked; ++cycle) {
    ASSERT_EQ(wrapper.update(movingState(home, cycle, 0.05, 0.5), kPeriod, torque.span()),
              CycleStatus::kOk);
    braked = stage.brakeForce() > 0.0;
  }
  ASSERT_TRUE(braked) << "the replayed motion never passed 0.85 v_max";
  const double limit = stage.limit();
  JointState bad = movingState(home, 501, 0.05, 0.5);
  bad.position[0] = std::nan("");
  EXPECT_EQ(wrapper.update(bad, kPeriod, torque.span()), CycleStatus::kFault);
  EXPECT_EQ(stage.brakeForce(), 0.0);
  EXPECT_EQ(stage.share(), 1.0);
  EXPECT_EQ(stage.limit(), limit);
}

TEST(ContactSpeed, TheBodysMassRaisesTheLimitAsTheReducedMassSays) {
  HomeFr3 clamped(kOn);
  HomeFr3 free_hand(kOn + "  body_mass: true\n");
  ContactSpeed clamped_stage(clamped.parameters(), kFr3Dof, true);
  ContactSpeed free_stage(free_hand.parameters(), kFr3Dof, true);
  Vector6d twist = Vector6d::Zero();
  twist[2] = -0.01;
  JointVector law = JointVector::Zero(kFr3Dof);
  JointVector torque = JointVector::Zero(kFr3Dof);
  (void)clamped_stage.apply(clamped.data(), twist, kPeriodS, law, torque);
  (void)free_stage.apply(free_hand.data(), twist, kPeriodS, law, torque);
  const double arm_kg = clamped_stage.mass();
  EXPECT_NEAR(free_stage.mass(), 1.0 / (1.0 / 0.6 + 1.0 / arm_kg), 1e-12);
  EXPECT_NEAR(free_stage.limit() / clamped_stage.limit(), std::sqrt(arm_kg / free_stage.mass()),
              1e-12);
}

}  // namespace
}  // namespace comply::pipeline
