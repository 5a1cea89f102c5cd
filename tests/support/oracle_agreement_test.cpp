// The oracles checked before they are trusted: KDL and MuJoCo against the textbook closed forms
// of a planar two-link arm, and against each other on the FR3.

#include <gtest/gtest.h>
#include <unistd.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "kdl_reference.hpp"
#include "max_error.hpp"
#include "mujoco_reference.hpp"

namespace comply::testing {
namespace {

// Planar two-link arm moving in the base x-z plane. Both joints turn about -y, so a positive
// angle lifts a link from +x towards +z and the textbook formulas apply with (x, y) -> (x, z).
constexpr double kBaseHeight = 0.2;  // joint 1 above the base origin
constexpr double kL1 = 0.9;          // joint 1 -> joint 2
constexpr double kL2 = 0.7;          // joint 2 -> tip
constexpr double kM1 = 2.5;
constexpr double kM2 = 1.7;
constexpr double kC1 = 0.35;  // COM distances along each link
constexpr double kC2 = 0.3;
constexpr double kI1 = 0.11;  // link 1 inertia about its COM, about y
constexpr double kIxx2 = 0.05, kIyy2 = 0.06, kIzz2 = 0.03;
constexpr double kRoll2 = 0.5;  // link 2's principal axes are turned about x by this much

/// Link 2's inertia about the y axis: its principal axes are rolled about x, so the y-y entry
/// mixes the principal moments about y and z.
double linkTwoInertia() {
  return kIyy2 * std::cos(kRoll2) * std::cos(kRoll2) + kIzz2 * std::sin(kRoll2) * std::sin(kRoll2);
}

// Parts that must not change the answer: the base inertia (fixed base), link 2's COM offset
// along the joint axis and its rolled principal axes, a massless tip link that carries a
// collision sphere (MuJoCo must not derive a mass from it), and no <mujoco> element (the
// reference must add one itself).
const char* const kTwoLinkUrdf = R"(<?xml version="1.0"?>
<!-- a comment with <robot name="decoy"> inside, which the <mujoco> insertion must skip -->
<robot name="planar_two_link">
  <link name="base">
    <inertial><origin xyz="0.1 0.2 0.3"/><mass value="5.0"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <link name="link1">
    <inertial><origin xyz="0.35 0 0"/><mass value="2.5"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.11" iyz="0" izz="0.10"/></inertial>
    <collision><origin xyz="0.45 0 0"/><geometry><box size="0.9 0.05 0.05"/></geometry></collision>
  </link>
  <link name="link2">
    <inertial><origin xyz="0.3 0.05 0" rpy="0.5 0 0"/><mass value="1.7"/>
      <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.06" iyz="0" izz="0.03"/></inertial>
  </link>
  <link name="tip">
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="joint1" type="revolute">
    <parent link="base"/><child link="link1"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 -1 0"/>
    <limit lower="-3.1" upper="3.1" effort="100" velocity="3"/>
  </joint>
  <joint name="joint2" type="continuous">
    <parent link="link1"/><child link="link2"/>
    <origin xyz="0.9 0 0"/><axis xyz="0 -1 0"/>
    <dynamics damping="0.7" friction="0.3"/>
  </joint>
  <joint name="tip_joint" type="fixed">
    <parent link="link2"/><child link="tip"/>
    <origin xyz="0.7 0 0"/>
  </joint>
</robot>
)";

/// Closed forms of the two-link arm (e.g. Spong, Hutchinson, Vidyasagar, ch. 7.4).
ReferenceResult analyticTwoLink(const Eigen::Vector2d& q, const Eigen::Vector2d& dq) {
  constexpr double g = kReferenceGravity;
  const double i2 = linkTwoInertia();
  const double c1 = std::cos(q(0)), s1 = std::sin(q(0));
  const double c2 = std::cos(q(1)), s2 = std::sin(q(1));
  const double c12 = std::cos(q(0) + q(1)), s12 = std::sin(q(0) + q(1));

  ReferenceResult r;
  r.position = Eigen::Vector3d(kL1 * c1 + kL2 * c12, 0.0, kBaseHeight + kL1 * s1 + kL2 * s12);
  r.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(q(0) + q(1), -Eigen::Vector3d::UnitY()));
  r.jacobian.setZero(6, 2);
  r.jacobian.col(0) << -kL1 * s1 - kL2 * s12, 0.0, kL1 * c1 + kL2 * c12, 0.0, -1.0, 0.0;
  r.jacobian.col(1) << -kL2 * s12, 0.0, kL2 * c12, 0.0, -1.0, 0.0;

  r.mass_matrix.resize(2, 2);
  r.mass_matrix(0, 0) =
      kM1 * kC1 * kC1 + kM2 * (kL1 * kL1 + kC2 * kC2 + 2.0 * kL1 * kC2 * c2) + kI1 + i2;
  r.mass_matrix(0, 1) = kM2 * (kC2 * kC2 + kL1 * kC2 * c2) + i2;
  r.mass_matrix(1, 0) = r.mass_matrix(0, 1);
  r.mass_matrix(1, 1) = kM2 * kC2 * kC2 + i2;

  const double h = -kM2 * kL1 * kC2 * s2;
  r.coriolis.resize(2);
  r.coriolis << h * (2.0 * dq(0) * dq(1) + dq(1) * dq(1)), -h * dq(0) * dq(0);

  // dV/dq with V = g (m1 z1 + m2 z2): the torque that holds the arm still.
  r.gravity.resize(2);
  r.gravity << g * ((kM1 * kC1 + kM2 * kL1) * c1 + kM2 * kC2 * c12), g * kM2 * kC2 * c12;
  return r;
}

// MuJoCo 2.2.2 stores each body inertia as principal moments plus principal axes (body_iquat),
// and its 3x3 eigensolver (mju_eig3) stops early on the axes (~1e-6 rad): on the FR3 the
// rebuilt inertia tensors differ from the URDF's by up to 1.6e-8 kg m^2 (eigenvalues exact,
// masses and COMs exact). M inherits that error directly and C(q, dq) dq scaled by dq^2; g(q)
// and the kinematics do not depend on rotational inertia and stay at round-off.
constexpr double kMujocoInertiaTolerance = 1e-6;

/// The two-link URDF in a file of its own, removed at the end of the test.
class TwoLinkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = std::filesystem::temp_directory_path() /
            ("comply_oracle_two_link_" + std::to_string(::getpid()) + ".urdf");
    std::ofstream(path_) << kTwoLinkUrdf;
  }
  void TearDown() override { std::filesystem::remove(path_); }

  std::string path() const { return path_.string(); }

  /// Joint states covering all quadrants, including both the arm stretched and folded.
  static std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> states() {
    std::mt19937 engine(11);
    std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi),
        speed(-3.0, 3.0);
    std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> result{
        {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
        {Eigen::Vector2d(0.0, std::numbers::pi), Eigen::Vector2d(1.0, -2.0)}};
    for (int i = 0; i < 200; ++i) {
      result.emplace_back(Eigen::Vector2d(angle(engine), angle(engine)),
                          Eigen::Vector2d(speed(engine), speed(engine)));
    }
    return result;
  }

  std::filesystem::path path_;
};

TEST_F(TwoLinkTest, KdlMatchesClosedForms) {
  const KdlReference kdl(path(), "base", "tip", {"joint1", "joint2"});
  EXPECT_EQ(kdl.dof(), 2);
  MaxError error;
  for (const auto& [q, dq] : states()) {
    error.add(kdl.compute(q, dq), analyticTwoLink(q, dq));
  }
  error.print("two-link KDL vs closed form");
  error.expectWithin(1e-9, 1e-9);
}

TEST_F(TwoLinkTest, MujocoMatchesClosedForms) {
  const MujocoReference mujoco(path(), "tip", {"joint1", "joint2"});
  EXPECT_EQ(mujoco.dof(), 2);
  MaxError error;
  for (const auto& [q, dq] : states()) {
    error.add(mujoco.compute(q, dq), analyticTwoLink(q, dq));
  }
  error.print("two-link MuJoCo vs closed form");
  error.expectWithin(1e-9, kMujocoInertiaTolerance);
  EXPECT_LE(error.mass_matrix, 1e-7);
}

TEST_F(TwoLinkTest, GravityIsTheHoldingTorque) {
  // Arm stretched out along +x: gravity pulls it down, so holding it takes a positive torque
  // about -y (the positive direction lifts the arm). Guards the sign convention of both oracles.
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  const double expected = kReferenceGravity * (kM1 * kC1 + kM2 * (kL1 + kC2));
  EXPECT_NEAR(
      KdlReference(path(), "base", "tip", {"joint1", "joint2"}).compute(zero, zero).gravity(0),
      expected, 1e-12);
  EXPECT_NEAR(MujocoReference(path(), "tip", {"joint1", "joint2"}).compute(zero, zero).gravity(0),
              expected, 1e-12);
}

TEST_F(TwoLinkTest, JointVectorsFollowTheGivenOrder) {
  const Eigen::Vector2d q(0.4, -1.3), dq(0.7, 2.1);
  const Eigen::Vector2d q_swapped(q(1), q(0)), dq_swapped(dq(1), dq(0));
  const ReferenceResult expected = analyticTwoLink(q, dq);

  const auto check = [&](const ReferenceResult& swapped, double tolerance) {
    EXPECT_LE(maxAbs(swapped.position - expected.position), 1e-12);
    EXPECT_LE(maxAbs(swapped.jacobian.col(0) - expected.jacobian.col(1)), 1e-12);
    EXPECT_LE(maxAbs(swapped.jacobian.col(1) - expected.jacobian.col(0)), 1e-12);
    EXPECT_NEAR(swapped.gravity(0), expected.gravity(1), 1e-12);
    EXPECT_NEAR(swapped.coriolis(0), expected.coriolis(1), tolerance);
    EXPECT_NEAR(swapped.mass_matrix(0, 0), expected.mass_matrix(1, 1), tolerance);
    EXPECT_NEAR(swapped.mass_matrix(1, 1), expected.mass_matrix(0, 0), tolerance);
    EXPECT_NEAR(swapped.mass_matrix(0, 1), expected.mass_matrix(1, 0), tolerance);
  };
  check(KdlReference(path(), "base", "tip", {"joint2", "joint1"}).compute(q_swapped, dq_swapped),
        1e-12);
  check(MujocoReference(path(), "tip", {"joint2", "joint1"}).compute(q_swapped, dq_swapped), 1e-7);
}

TEST_F(TwoLinkTest, KdlRejectsBadInput) {
  EXPECT_THROW(KdlReference("/nonexistent.urdf", "base", "tip", {"joint1", "joint2"}),
               std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "nowhere", {"joint1", "joint2"}), std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "tip", {"joint1"}), std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "tip", {"joint1", "joint3"}), std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "tip", {"joint1", "tip_joint"}), std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "tip", {"joint1", "joint1"}), std::runtime_error);
  EXPECT_THROW(KdlReference(path(), "base", "link1", {"joint1", "joint2"}), std::runtime_error);
  const KdlReference kdl(path(), "base", "tip", {"joint1", "joint2"});
  EXPECT_THROW(kdl.compute(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)), std::runtime_error);
}

TEST_F(TwoLinkTest, MujocoRejectsBadInput) {
  EXPECT_THROW(MujocoReference("/nonexistent.urdf", "tip", {"joint1"}), std::runtime_error);
  EXPECT_THROW(MujocoReference(path(), "nowhere", {"joint1"}), std::runtime_error);
  EXPECT_THROW(MujocoReference(path(), "tip", {"joint3"}), std::runtime_error);
  EXPECT_THROW(MujocoReference(path(), "tip", {"tip_joint"}), std::runtime_error);
  EXPECT_THROW(MujocoReference(path(), "tip", {"joint1", "joint1"}), std::runtime_error);
  const MujocoReference mujoco(path(), "tip", {"joint1", "joint2"});
  EXPECT_THROW(mujoco.compute(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1)),
               std::runtime_error);

  // MuJoCo's compiler message must reach the caller.
  const std::filesystem::path broken =
      std::filesystem::temp_directory_path() /
      ("comply_oracle_broken_" + std::to_string(::getpid()) + ".urdf");
  std::ofstream(broken) << "<robot name=\"broken\"><link name=\"a\"/><joint name=\"j\" "
                           "type=\"revolute\"><parent link=\"a\"/><child link=\"missing\"/>"
                           "</joint></robot>";
  try {
    MujocoReference(broken.string(), "a", {});
    ADD_FAILURE() << "a joint to a missing link was accepted";
  } catch (const std::runtime_error& e) {
    std::cout << "MuJoCo's error for a broken URDF: " << e.what() << "\n";
    EXPECT_NE(std::string(e.what()).find("MuJoCo could not load"), std::string::npos);
  }
  std::filesystem::remove(broken);
}

TEST_F(TwoLinkTest, MujocoKeepsUrdfJointDynamicsOutOfTheRigidBodyTerms) {
  // joint2 has damping and friction in the URDF, which MuJoCo imports; neither may show up in
  // C(q, dq) dq, and the tip link and its collision sphere must stay massless.
  const MujocoReference mujoco(path(), "tip", {"joint1", "joint2"});
  const int tip = mj_name2id(mujoco.model(), mjOBJ_BODY, "tip");
  ASSERT_GE(tip, 0);
  EXPECT_EQ(mujoco.model()->body_mass[tip], 0.0);
  const Eigen::Vector2d q(0.3, 0.0), dq(0.0, 2.0);
  // With dq1 = 0 and q2 = 0: c = (h (2 dq1 dq2 + dq2^2), -h dq1^2) = (0, 0) since h ~ sin(q2).
  EXPECT_LE(maxAbs(mujoco.compute(q, dq).coriolis), 1e-12);
}

TEST(OracleAgreement, KdlAndMujocoAgreeOnFr3) {
  const std::filesystem::path urdf = std::filesystem::path(COMPLY_ROBOTS_DIR) / "fr3/fr3.urdf";
  if (!std::filesystem::exists(urdf)) {
    GTEST_SKIP() << urdf << " not found";
  }
  const std::vector<std::string> joints{"fr3_joint1", "fr3_joint2", "fr3_joint3", "fr3_joint4",
                                        "fr3_joint5", "fr3_joint6", "fr3_joint7"};
  const KdlReference kdl(urdf.string(), "fr3_link0", "fr3_link8", joints);
  const MujocoReference mujoco(urdf.string(), "fr3_link8", joints);

  std::mt19937 engine(5);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi),
      speed(-2.5, 2.5);
  MaxError error;
  double largest_gravity = 0.0, largest_coriolis = 0.0;
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd q(7), dq(7);
    for (int j = 0; j < 7; ++j) {
      q(j) = angle(engine);
      dq(j) = speed(engine);
    }
    const ReferenceResult a = kdl.compute(q, dq);
    error.add(a, mujoco.compute(q, dq));
    largest_gravity = std::max(largest_gravity, maxAbs(a.gravity));
    largest_coriolis = std::max(largest_coriolis, maxAbs(a.coriolis));
  }
  error.print("fr3 KDL vs MuJoCo over 100 states");
  std::cout << "  (for scale: largest |g| " << largest_gravity << " N m, largest |C dq| "
            << largest_coriolis << " N m)\n";
  error.expectWithin(1e-9, kMujocoInertiaTolerance);
  EXPECT_LE(error.mass_matrix, 1e-7);
}

/// Every robot shipped in robots/<name>/robot.yaml, base frame to TCP: a wider check of the two
/// oracles (other joint conventions, rotated joint origins, fixed frames on the way to the tip).
class ShippedRobotTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedRobotTest, KdlAndMujocoAgree) {
  const std::filesystem::path folder = std::filesystem::path(COMPLY_ROBOTS_DIR) / GetParam();
  const YAML::Node robot = YAML::LoadFile((folder / "robot.yaml").string());
  const std::string urdf = (folder / robot["urdf"].as<std::string>()).string();
  const auto joints = robot["joints"].as<std::vector<std::string>>();
  const auto base = robot["base_frame"].as<std::string>();
  const auto tcp = robot["tcp_frame"].as<std::string>();
  // MuJoCo reports in the frame of the URDF root link, KDL in `base`: they must be the same.
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(urdf);
  ASSERT_TRUE(model);
  ASSERT_EQ(model->getRoot()->name, base) << "MuJoCo's world frame is the root link";

  const KdlReference kdl(urdf, base, tcp, joints);
  const MujocoReference mujoco(urdf, tcp, joints);
  std::mt19937 engine(17);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi),
      speed(-2.5, 2.5);
  MaxError error;
  const auto n = static_cast<Eigen::Index>(joints.size());
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd q(n), dq(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      q(j) = angle(engine);
      dq(j) = speed(engine);
    }
    error.add(kdl.compute(q, dq), mujoco.compute(q, dq));
  }
  error.print(GetParam() + " KDL vs MuJoCo over 100 states");
  error.expectWithin(1e-9, kMujocoInertiaTolerance);
  EXPECT_LE(error.mass_matrix, 1e-7);
}

std::vector<std::string> shippedRobots() {
  std::vector<std::string> names;
  if (std::filesystem::is_directory(COMPLY_ROBOTS_DIR)) {
    for (const auto& entry : std::filesystem::directory_iterator(COMPLY_ROBOTS_DIR)) {
      if (std::filesystem::exists(entry.path() / "robot.yaml")) {
        names.push_back(entry.path().filename().string());
      }
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Robots, ShippedRobotTest, ::testing::ValuesIn(shippedRobots()),
                         [](const auto& robot) { return robot.param; });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ShippedRobotTest);

}  // namespace
}  // namespace comply::testing
