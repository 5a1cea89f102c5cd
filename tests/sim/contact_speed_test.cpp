// The contact-speed stage on the simulated FR3 (contact_speed.hpp): the mass it computes against
// MuJoCo's own inertia of the plant (which has the rotors' armature), and a probe driven into a
// hand's spring (spring_contact.hpp) with the stage and without. The full sweep over speeds and
// poses is contact_speed_sweep_test.cpp (label long).

#include "comply/pipeline/contact_speed.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include "comply/pipeline/controller.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "spring_contact.hpp"

namespace comply::testing {
namespace {

// MuJoCo imports the same URDF and the same armature; what differs is the importer's inertia
// balancing and rounding. 1 % holds with a wide margin (the largest difference is printed).
constexpr double kMassTolerance = 0.01;

/// MuJoCo's mass along `u` at the plant's TCP body at `joints`: (u^T J_p M^-1 J_p^T u)^-1, M from
/// mj_fullM (armature included), M^-1 by mj_solveM.
double mujocoMass(const mjModel& model, const std::vector<double>& joints,
                  const std::vector<std::string>& names, const Eigen::Vector3d& u) {
  mjData* data = mj_makeData(&model);
  for (std::size_t i = 0; i < names.size(); ++i) {
    data->qpos[model.jnt_qposadr[mj_name2id(&model, mjOBJ_JOINT, names[i].c_str())]] = joints[i];
  }
  mj_forward(&model, data);
  const int nv = model.nv;
  std::vector<mjtNum> jacp(static_cast<std::size_t>(3 * nv));
  mj_jacBody(&model, data, jacp.data(), nullptr, mj_name2id(&model, mjOBJ_BODY, "fr3_tcp"));
  std::vector<mjtNum> dense(static_cast<std::size_t>(nv * nv));
  mj_fullM(&model, dense.data(), data->qM);
  std::vector<mjtNum> jt_u(static_cast<std::size_t>(nv));
  for (int j = 0; j < nv; ++j) {
    jt_u[j] = jacp[j] * u.x() + jacp[nv + j] * u.y() + jacp[2 * nv + j] * u.z();
  }
  std::vector<mjtNum> solved(jt_u);
  mj_solveM(&model, data, solved.data(), jt_u.data(), 1);
  double inverse = 0.0;
  for (int j = 0; j < nv; ++j) {
    inverse += jt_u[j] * solved[j];
  }
  // The dense matrix agrees with the factor mj_solveM used: the product is M^-1 J^T u.
  Eigen::Map<const Eigen::Matrix<mjtNum, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> m(
      dense.data(), nv, nv);
  const Eigen::Map<const Eigen::VectorXd> x(solved.data(), nv);
  const Eigen::Map<const Eigen::VectorXd> b(jt_u.data(), nv);
  EXPECT_LE((m * x - b).norm(), 1e-9 * b.norm());
  mj_deleteData(data);
  return 1.0 / inverse;
}

TEST(ContactSpeedOnTheFr3, TheReflectedMassAgreesWithMujocosInertiaOfThePlant) {
  const pipeline::WrapperConfig config = springConfig(true);
  const sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  const model::RobotDescription& robot = *config.robot_description;
  pipeline::Controller controller(pipeline::resolveController(config));
  // The stage reads the laws' M, rotors included; taken off again, the links alone.
  const std::vector<double>& rotors = controller.model().armature();
  ASSERT_EQ(rotors.size(), static_cast<std::size_t>(controller.dof()));
  JointVector without_rotors = JointVector::Zero(controller.dof());
  for (int i = 0; i < controller.dof(); ++i) {
    without_rotors[i] = -rotors[static_cast<std::size_t>(i)];
  }
  double worst = 0.0;
  for (const ArmPose& pose : springPoses()) {
    JointState state = JointState::zero(controller.dof());
    for (int i = 0; i < controller.dof(); ++i) {
      state.position[i] = pose.joints[static_cast<std::size_t>(i)];
    }
    controller.activate(state);
    const model::Data& data = controller.modelData();
    const std::vector<Eigen::Vector3d> directions = {
        Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
        Eigen::Vector3d(1.0, -1.0, 1.0).normalized(), data.tip_rotation.col(2)};
    for (const Eigen::Vector3d& u : directions) {
      const double reference = mujocoMass(plant.mujocoModel(), pose.joints, robot.joints, u);
      const double ours = pipeline::reflectedMass(data, JointVector(), controller.dof(), u);
      EXPECT_NEAR(ours, reference, kMassTolerance * reference) << pose.name << " " << u.transpose();
      worst = std::max(worst, std::abs(ours / reference - 1.0));
      // Without the rotors the mass is far too small: the limit would be too fast.
      const double links = pipeline::reflectedMass(data, without_rotors, controller.dof(), u);
      EXPECT_LT(links, 0.85 * reference) << pose.name << " " << u.transpose();
      std::cout << pose.name << " u = " << u.transpose() << ": mu " << ours << " kg (MuJoCo "
                << reference << ", links alone " << links << ")\n";
    }
  }
  std::ostringstream largest;
  largest << std::scientific << std::setprecision(2) << worst;
  RecordProperty("largest_relative_difference", largest.str());
  std::cout << "largest relative difference " << largest.str() << "\n";
}

class SpringAtHome : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new SpringScene(springScene(
        springPoses()[0], std::filesystem::temp_directory_path() / "comply_contact_speed_test"));
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  static SpringScene* scene_;
};
SpringScene* SpringAtHome::scene_ = nullptr;

TEST_F(SpringAtHome, At0_6MetresPerSecondTheStageKeepsTheForceUnderTheHandsLimit) {
  const SpringRun off = driveIntoSpring(*scene_, springConfig(false), 0.6);
  const SpringRun on = driveIntoSpring(*scene_, springConfig(true), 0.6);
  for (const SpringRun& run : {off, on}) {
    ASSERT_TRUE(run.touched);
    EXPECT_FALSE(run.faulted);
  }
  // Without the stage the probe arrives fast and the spring passes 140 N, at least as far as the
  // energy model says (v sqrt(mu k), mu along the axis); the law's push behind it adds a little.
  EXPECT_GT(off.contact_speed_m_per_s, 0.45);
  EXPECT_GT(off.peak_force_n, kHandsQuasiStaticLimitN);
  const double predicted =
      off.contact_speed_m_per_s * std::sqrt(scene_->axis_mass_kg * kHandStiffnessNPerM);
  EXPECT_GT(off.peak_force_n, 0.95 * predicted);
  EXPECT_LT(off.peak_force_n, 1.3 * predicted);
  // With it the probe arrives below its limit and the spring stays under 140 N.
  EXPECT_GT(on.stage_cycles, 0U);
  EXPECT_LT(on.contact_speed_m_per_s, on.limit_m_per_s);
  EXPECT_LT(on.peak_force_n, kHandsQuasiStaticLimitN);
  // The quasi-static part: the law's 2000 N/m x 5 mm, in series with the spring: ~10 N.
  EXPECT_NEAR(on.settled_force_n, kStiffnessNPerM * kPastSurfaceM, 2.0);
  std::cout << "0.6 m/s at home: off " << off.peak_force_n << " N at " << off.contact_speed_m_per_s
            << " m/s (energy model " << predicted << " N, mu " << scene_->axis_mass_kg
            << " kg); on " << on.peak_force_n << " N at " << on.contact_speed_m_per_s
            << " m/s, v_max " << on.limit_m_per_s << " m/s\n";
}

TEST_F(SpringAtHome, SlowTrackingIsTheSameRunBitForBitWithTheStageOn) {
  const SpringRun off = driveIntoSpring(*scene_, springConfig(false), 0.05);
  const SpringRun on = driveIntoSpring(*scene_, springConfig(true), 0.05);
  ASSERT_TRUE(on.touched);
  EXPECT_EQ(on.stage_cycles, 0U);
  EXPECT_GT(on.slowest_limit_m_per_s, 2.0 * 0.05) << "the run must stay below half the limit";
  EXPECT_EQ(on.peak_force_n, off.peak_force_n);
  EXPECT_EQ(on.settled_force_n, off.settled_force_n);
  EXPECT_LT(on.peak_force_n, kHandsQuasiStaticLimitN);
}

}  // namespace
}  // namespace comply::testing
