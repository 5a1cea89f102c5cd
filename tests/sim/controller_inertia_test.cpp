// The controller's M(q) is the arm's, its rotors included (robot.yaml joint_dynamics.armature):
// equal to the MuJoCo plant's mj_fullM on every shipped robot and on a 7-DOF arm added by path,
// so a damping ratio designed on it is the one the plant gets. Before, the laws' M was the bare
// links' while the plant carried the rotors: on the FR3 the wrist's designed damping was a few
// hundredths of critical on the arm it damped, and every waypoint left a 10 Hz, 0.2 deg
// orientation ring. The admittance modes keep the bare links (their virtual arm has no rotors),
// and a robot that declares no rotor inertias is taken with a warning.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// A Gen3-like 7-DOF arm added by path (datasheet-sized links and drives), not on the search path.
const std::string kArmByPath = (kSourceDir / "tests" / "sim" / "robots" / "gen3like").string();

std::vector<std::string> robotsAndOneByPath() {
  std::vector<std::string> robots = model::availableRobots();
  robots.push_back(kArmByPath);
  return robots;
}

class ControllerInertia : public ::testing::TestWithParam<std::string> {};

TEST_P(ControllerInertia, TheControllersMassMatrixIsThePlants) {
  const auto resolved = pipeline::resolveController(simCartesianConfig(GetParam()));
  const model::Model& model = *resolved->model;
  ASSERT_FALSE(model.armature().empty());
  model::Data data(model);
  sim::SimulatedRobot plant(resolved->robot, sim::PlantOptions{});
  const mjModel& mujoco = plant.mujocoModel();
  std::vector<int> dof_address;
  for (const std::string& joint : model.jointNames()) {
    const int id = mj_name2id(&mujoco, mjOBJ_JOINT, joint.c_str());
    ASSERT_GE(id, 0) << joint;
    dof_address.push_back(mujoco.jnt_dofadr[id]);
  }
  std::vector<mjtNum> full(static_cast<std::size_t>(mujoco.nv * mujoco.nv));
  std::mt19937 random(11);
  double worst = 0.0;
  double worst_without_rotors = 0.0;
  for (int sample = 0; sample < 20; ++sample) {
    std::vector<double> q(resolved->robot.home);
    for (double& angle : q) {
      angle += std::uniform_real_distribution<double>(-0.4, 0.4)(random);
    }
    plant.setJointPositions(q);
    plant.forward();
    mj_fullM(&mujoco, full.data(), plant.mujocoData().qM);
    ASSERT_EQ(model::update(model, data, q, q, model::Quantity::kMassMatrix),
              model::UpdateStatus::kOk);
    for (int i = 0; i < model.dof(); ++i) {
      for (int j = 0; j < model.dof(); ++j) {
        const double plant_entry =
            full[static_cast<std::size_t>(dof_address[static_cast<std::size_t>(i)] * mujoco.nv +
                                          dof_address[static_cast<std::size_t>(j)])];
        const double error = std::abs(data.mass_matrix(i, j) - plant_entry);
        worst = std::max(worst, error);
        const double rotor = i == j ? model.armature()[static_cast<std::size_t>(i)] : 0.0;
        worst_without_rotors = std::max(worst_without_rotors, std::abs(error - rotor));
      }
    }
  }
  // The plant holds each body's inertia as MuJoCo's principal moments and axes, rounded: within
  // 1e-6 kg m^2 of the URDF's, on entries of 0.01 to a few kg m^2.
  EXPECT_LT(worst, 2e-6) << GetParam();
  // The bare links would miss the plant by the rotors: the largest declared one.
  EXPECT_GT(worst_without_rotors, 0.02) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Robots, ControllerInertia, ::testing::ValuesIn(robotsAndOneByPath()),
                         [](const auto& test) {
                           return std::filesystem::path(test.param).filename().string();
                         });

/// The overshoot [share of the step] of the TCP's turn about its z axis after a step of `step_rad`
/// of the orientation reference, critically damped (ratio 1) at `stiffness` N m/rad, on a plant
/// of `plant_robot` (its rotors included).
double turnOvershoot(const model::RobotDescription& plant_robot,
                     const pipeline::WrapperConfig& config, double step_rad, double stiffness) {
  sim::SimulatedRobot plant(plant_robot, sim::PlantOptions{});
  pipeline::CartesianWrapper wrapper(config);
  const int dof = wrapper.dof();
  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  const Eigen::Quaterniond start = wrapper.measuredPose().tcp_orientation;
  const Eigen::Quaterniond target = start * Eigen::AngleAxisd(step_rad, Eigen::Vector3d::UnitZ());
  CartesianCommand command = CartesianCommand::zero(dof);
  command.stamp_s = 1.0;
  command.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping;
  command.position = wrapper.measuredPose().tcp_position;
  command.orientation = target;
  command.stiffness_translational = 3000.0 * Eigen::Matrix3d::Identity();
  command.stiffness_rotational = stiffness * Eigen::Matrix3d::Identity();
  command.damping_mode = DampingMode::kRatio;
  command.damping_ratio.setOnes();
  EXPECT_TRUE(wrapper.submit(command).accepted);
  JointVector torque = JointVector::Zero(dof);
  double largest_turn = 0.0;
  for (int cycle = 0; cycle < 1000; ++cycle) {
    plant.read(state);
    EXPECT_NE(wrapper.update(state, plant.controlPeriod(),
                             {torque.data(), static_cast<std::size_t>(dof)}),
              pipeline::CycleStatus::kFault);
    plant.write({torque.data(), static_cast<std::size_t>(dof)});
    plant.step();
    const Eigen::AngleAxisd turned(start.conjugate() * wrapper.measuredPose().tcp_orientation);
    largest_turn = std::max(largest_turn, turned.angle() * turned.axis().z());
  }
  return largest_turn / step_rad - 1.0;
}

TEST(ControllerInertia, ACriticallyDampedTurnOfTheWristDoesNotOvershoot) {
  // 300 N m/rad (config/sim/cartesian_impedance.yaml) on a 0.05 rad turn. With the rotors in M
  // the FR3's wrist comes to 99.8 % of the turn and no further; without them (the law's damping a
  // few hundredths of critical on the plant) it swings 138 % past it.
  const pipeline::WrapperConfig config = simCartesianConfig("fr3");
  const model::RobotDescription& fr3 = *config.robot_description;
  EXPECT_LT(turnOvershoot(fr3, config, 0.05, 300.0), 0.05);
  pipeline::WrapperConfig bare = config;
  auto description = std::make_shared<model::RobotDescription>(*config.robot_description);
  description->joint_dynamics->armature.assign(description->joints.size(), 0.0);
  bare.robot_description = description;  // the law's M without rotors; the plant keeps them
  EXPECT_GT(turnOvershoot(fr3, bare, 0.05, 300.0), 0.3);
}

TEST(ControllerInertia, AnAdmittanceLawsModelIsItsVirtualArmsBareLinks) {
  pipeline::WrapperConfig config = simCartesianConfig("ur5e");
  config.output.mode = OutputMode::kPosition;
  EXPECT_TRUE(pipeline::resolveController(config)->model->armature().empty());
  config.output.mode = OutputMode::kJointPd;
  EXPECT_EQ(pipeline::resolveController(config)->model->armature(),
            config.robot_description->joint_dynamics->armature);
}

TEST(ControllerInertia, ARobotWithoutRotorInertiasIsTakenWithAWarning) {
  // The Gen3-like arm's description without joint_dynamics: its bare wrist is a few 1e-4 kg m^2,
  // on which every robot's default rotational stiffness would be refused. The translational
  // gains stay bounded; the rotational ones are not, and the warning says so.
  // The option table's defaults (30 N m/rad) and config/sim/cartesian_impedance.yaml (300).
  const auto configFor = [](bool defaults) {
    return defaults ? host::controllerConfig(kArmByPath, "cartesian_impedance", "")
                    : simCartesianConfig(kArmByPath);
  };
  for (const bool defaults : {true, false}) {
    SCOPED_TRACE(defaults ? "defaults" : "config/sim/cartesian_impedance.yaml");
    pipeline::WrapperConfig config = configFor(defaults);
    auto description = std::make_shared<model::RobotDescription>(*config.robot_description);
    description->joint_dynamics.reset();
    config.robot_description = description;
    std::shared_ptr<const pipeline::ResolvedController> resolved;
    ASSERT_NO_THROW(resolved = pipeline::resolveController(config));
    ASSERT_EQ(resolved->warnings.size(), 1U);
    EXPECT_NE(resolved->warnings[0].find("gen3like declares no rotor inertias"), std::string::npos)
        << resolved->warnings[0];
    EXPECT_NE(resolved->warnings[0].find("rotational, joint and nullspace gains are not"),
              std::string::npos)
        << resolved->warnings[0];
    EXPECT_TRUE(resolved->gain_bound.bare_links);
    EXPECT_TRUE(std::isinf(resolved->gain_bound.rotational_inertia_kg_m2));
    EXPECT_GT(resolved->gain_bound.translational_mass_kg, 0.1);
    // The governor and the stability guard keep the arm's own (bare) inertias.
    EXPECT_TRUE(std::isfinite(resolved->parameters.tcp_inertia_kg_m2));
    // With its rotor inertias declared: no warning, every gain bounded.
    const auto declared = pipeline::resolveController(configFor(defaults));
    EXPECT_TRUE(declared->warnings.empty());
    EXPECT_FALSE(declared->gain_bound.bare_links);
  }
}

}  // namespace
}  // namespace comply::testing
