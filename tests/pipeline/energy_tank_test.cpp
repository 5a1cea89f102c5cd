// The energy tank on its own (energy_tank.hpp), against numbers worked by hand: it pays for an
// increase of stiffness or a turn of the task frame while it can, scales back what it cannot,
// credits a decrease only with what it paid, and refills from the damping's dissipation bound
// net of the sampled spring's share, never from a window shaping clipped.

#include "comply/pipeline/energy_tank.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "comply/model/model.hpp"
#include "comply/pipeline/task_stiffness.hpp"
#include "test_urdfs.hpp"

namespace comply::pipeline {
namespace {

constexpr double kPeriodS = 1e-3;

PassivityConfig passivity() {
  PassivityConfig config;
  config.enabled = true;
  config.tank_initial_j = 1.0;
  config.tank_max_j = 2.0;
  config.tank_min_j = 0.01;
  config.nullspace_tank_initial_j = 0.5;
  config.nullspace_tank_max_j = 1.0;
  return config;
}

/// A tank reset on a one-joint arm at rest at q = 0 with its tool at the origin.
class EnergyTankTest : public ::testing::Test {
 protected:
  EnergyTankTest() : model_(load()), data_(model_), tank_(passivity()) {
    state_.position = JointVector::Zero(1);
    tank_.reset(data_, state_);
  }

  static model::Model load() {
    model::ModelOptions options;
    options.joint_names = {"hinge"};
    options.tip_frame = "tip";
    return model::Model::fromUrdfString(test_urdfs::pendulum(), options);
  }

  /// A joint command with its spring at rest 0.1 rad from the arm, of stiffness `stiffness`.
  static comply_joint_command jointLaw(double stiffness, double damping = 0.0) {
    comply_joint_command law{};
    law.dof = 1;
    law.position[0] = 0.1;
    law.stiffness[0] = stiffness;
    law.damping[0] = damping;
    return law;
  }

  static JointVector one(double value) { return JointVector::Constant(1, value); }

  model::Model model_;
  model::Data data_;
  JointState state_;
  EnergyTank tank_;
};

TEST_F(EnergyTankTest, PaysAnIncreaseItCanAfford) {
  // 1/2 (100 - 0) 0.1^2 = 0.5 J of the 1 J it holds.
  EXPECT_EQ(tank_.payJointChange(jointLaw(0.0), state_, one(100.0)), 1.0);
  EXPECT_NEAR(tank_.task().energy_j, 0.5, 1e-15);
  EXPECT_NEAR(tank_.injected(), 0.5, 1e-15);
  EXPECT_EQ(tank_.refused(), 0.0);
}

TEST_F(EnergyTankTest, ScalesBackWhatItCannotPayAndKeepsItsFloor) {
  tank_.payJointChange(jointLaw(0.0), state_, one(100.0));
  tank_.beginCycle();
  // 100 -> 500 would inject 2 J; 0.5 - 0.01 J is what it can spend.
  const double beta = tank_.payJointChange(jointLaw(100.0), state_, one(500.0));
  EXPECT_NEAR(beta, 0.49 / 2.0, 1e-15);
  EXPECT_NEAR(tank_.task().energy_j, 0.01, 1e-15);
  EXPECT_NEAR(tank_.refused(), 2.0 - 0.49, 1e-15);
  // From where the gains stopped, 100 + 0.245 * 400, at its floor it pays nothing more.
  EXPECT_NEAR(tank_.payJointChange(jointLaw(198.0), state_, one(500.0)), 0.0, 1e-15);
}

TEST_F(EnergyTankTest, ADecreaseGivesBackOnlyWhatItPaid) {
  tank_.payJointChange(jointLaw(0.0), state_, one(100.0));  // pays 0.5 J
  // 1000 -> 0 releases 5 J, of which 0.5 J were paid from here.
  EXPECT_EQ(tank_.payJointChange(jointLaw(1000.0), state_, one(0.0)), 1.0);
  EXPECT_NEAR(tank_.task().energy_j, 1.0, 1e-15);
  EXPECT_NEAR(tank_.task().outstanding_j, 0.0, 1e-15);
}

TEST_F(EnergyTankTest, TheNullspaceHasItsOwnAccount) {
  comply_cartesian_command law{};
  law.dof = 1;
  law.nullspace_position[0] = 0.1;
  // 1/2 200 0.1^2 = 1 J: more than the nullspace's 0.5 J, however full the task account is.
  EXPECT_NEAR(tank_.payNullspaceChange(law, state_, one(200.0)), 0.49, 1e-15);
  EXPECT_NEAR(tank_.nullspace().energy_j, 0.01, 1e-15);
  EXPECT_EQ(tank_.task().energy_j, 1.0);
}

TEST_F(EnergyTankTest, AMoveOfTheNullspaceTargetIsPaidFromTheNullspaceAccount) {
  comply_cartesian_command law{};
  law.dof = 1;
  law.nullspace_stiffness[0] = 40.0;
  // 0 -> 0.1 rad from the arm at 0: 1/2 40 0.1^2 = 0.2 J of the nullspace's 0.5 J.
  EXPECT_EQ(tank_.payNullspaceMove(law, state_, one(0.1)), 1.0);
  EXPECT_NEAR(tank_.nullspace().energy_j, 0.3, 1e-15);
  EXPECT_EQ(tank_.task().energy_j, 1.0);
  // 0.1 -> 0.2 rad: 1/2 40 (0.2^2 - 0.1^2) = 0.6 J, more than the 0.29 J it can spend; the
  // fraction beta injects 0.4 beta + 0.2 beta^2 (convex), and the secant's beta = 0.29 / 0.6
  // is payable.
  tank_.beginCycle();
  law.nullspace_position[0] = 0.1;
  const double beta = tank_.payNullspaceMove(law, state_, one(0.2));
  EXPECT_NEAR(beta, 0.29 / 0.6, 1e-15);
  const double paid = 0.4 * beta + 0.2 * beta * beta;
  EXPECT_NEAR(tank_.nullspace().energy_j, 0.3 - paid, 1e-15);
  EXPECT_NEAR(tank_.refused(), 0.6 - paid, 1e-15);
  // Back onto the arm, 0.1 -> 0: the 0.2 J the spring held come back (all of it was paid).
  tank_.beginCycle();
  EXPECT_EQ(tank_.payNullspaceMove(law, state_, one(0.0)), 1.0);
  EXPECT_NEAR(tank_.nullspace().energy_j, 0.5 - paid, 1e-15);
  // Without a spring a move costs nothing.
  law.nullspace_stiffness[0] = 0.0;
  EXPECT_EQ(tank_.payNullspaceMove(law, state_, one(3.0)), 1.0);
  EXPECT_NEAR(tank_.nullspace().energy_j, 0.5 - paid, 1e-15);
}

TEST_F(EnergyTankTest, TurningTheFrameOfAnAnisotropicSpringIsPaidFor) {
  comply_cartesian_command law{};
  law.dof = 1;
  law.orientation[3] = 1.0;
  data_.tip_position = Eigen::Vector3d(0.1, 0.0, 0.0);  // 0.1 m from the command along base x
  TaskStiffness along_y{};
  along_y.translational[0] = 100.0;  // stiff along task x only, task x = base y
  along_y.frame = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ());
  TaskStiffness along_x = along_y;
  along_x.frame = Eigen::Quaterniond::Identity();
  // The spring along y holds nothing at an error along x; turned onto x it holds 0.5 J.
  EXPECT_EQ(tank_.payTaskChange(law, data_, along_y, along_x), 1.0);
  EXPECT_NEAR(tank_.task().energy_j, 0.5, 1e-12);
  // An isotropic spring turns for free.
  TaskStiffness isotropic = along_x;
  isotropic.translational[4] = isotropic.translational[8] = 100.0;
  TaskStiffness turned = isotropic;
  turned.frame = along_y.frame;
  EXPECT_EQ(tank_.payTaskChange(law, data_, isotropic, turned), 1.0);
  EXPECT_NEAR(tank_.task().energy_j, 0.5, 1e-12);
}

TEST_F(EnergyTankTest, TheJointRefillCreditsTheDampingNetOfTheSampledSpring) {
  // Ten cycles of 1 mrad each against damping 10 and stiffness 100: the bound
  // d |dq|^2 / w = (10 - 0.5 T 100) 0.01^2 / 0.01.
  for (int cycle = 0; cycle < 10; ++cycle) {
    state_.position[0] += 0.001;
    tank_.refillJoint(jointLaw(100.0, 10.0), state_, kPeriodS, false);
  }
  EXPECT_NEAR(tank_.dissipated(), (10.0 - 0.05) * 0.01, 1e-12);
  EXPECT_NEAR(tank_.task().energy_j, 1.0 + 0.0995, 1e-12);
}

TEST_F(EnergyTankTest, AWindowWithAClippedTorqueCreditsNothing) {
  for (int cycle = 0; cycle < 10; ++cycle) {
    state_.position[0] += 0.001;
    tank_.refillJoint(jointLaw(0.0, 10.0), state_, kPeriodS, cycle == 5);
  }
  EXPECT_EQ(tank_.dissipated(), 0.0);
}

TEST_F(EnergyTankTest, TheCartesianRefillCountsMotionAwayFromTheCommandedTwistOnly) {
  comply_cartesian_command law{};
  law.dof = 1;
  law.damping_mode = COMPLY_DAMPING_ABSOLUTE;
  law.damping_translational[0] = law.damping_translational[4] = law.damping_translational[8] = 50;
  tank_.cacheBounds(law);
  const auto moveTenCycles = [&] {
    for (int cycle = 0; cycle < 10; ++cycle) {
      data_.tip_position.x() += 0.001;
      tank_.refillCartesian(law, data_, kPeriodS, false);
    }
  };
  moveTenCycles();  // 1 m/s against none commanded: 50 0.01^2 / 0.01
  EXPECT_NEAR(tank_.dissipated(), 0.5, 1e-12);
  law.twist[0] = 1.0;  // the same motion, commanded
  moveTenCycles();
  EXPECT_NEAR(tank_.dissipated(), 0.5, 1e-12);
}

}  // namespace
}  // namespace comply::pipeline
