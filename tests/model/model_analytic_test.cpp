// Closed-form kinematics and dynamics of tiny arms against the model, term by term.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "comply/model/update.hpp"
#include "test_urdfs.hpp"

namespace comply::model {
namespace {

constexpr double kG = 9.81;
constexpr double kTol = 1e-12;

Model load(const std::string& urdf, std::vector<std::string> joints, const std::string& tip,
           const Eigen::Isometry3d& tcp = Eigen::Isometry3d::Identity()) {
  ModelOptions options;
  options.joint_names = std::move(joints);
  options.tip_frame = tip;
  options.tcp_offset = tcp;
  return Model::fromUrdfString(urdf, options);
}

TEST(PendulumTest, MatchesHandComputation) {
  const Model model = load(test_urdfs::pendulum(), {"hinge"}, "tip");
  Data data(model);
  data.payload = {1.0, Eigen::Vector3d::Zero()};
  for (const double q : {-1.2, 0.0, 0.4, 2.5}) {
    const std::vector<double> position{q};
    const std::vector<double> velocity{0.7};
    ASSERT_EQ(update(model, data, position, velocity, Quantity::kAll), UpdateStatus::kOk);
    const double c = std::cos(q);
    const double s = std::sin(q);
    EXPECT_NEAR((data.tip_position - Eigen::Vector3d(c, 0.0, 1.0 - s)).norm(), 0.0, kTol);
    const Eigen::Quaterniond expected(Eigen::AngleAxisd(q, Eigen::Vector3d::UnitY()));
    EXPECT_NEAR(data.tip_orientation.angularDistance(expected), 0.0, 1e-9);
    // Holding torque of 2 kg at 0.5 m and of the 1 kg payload at the 1 m tip.
    EXPECT_NEAR(data.gravity[0], -2.0 * kG * 0.5 * c, kTol);
    EXPECT_NEAR(data.payload_gravity[0], -1.0 * kG * 1.0 * c, kTol);
    EXPECT_NEAR(data.mass_matrix(0, 0), 0.02 + 2.0 * 0.25, kTol);
    EXPECT_NEAR(data.coriolis[0], 0.0, kTol);  // one joint: no velocity coupling
    Eigen::Matrix<double, 6, 1> jacobian;
    jacobian << -s, 0.0, -c, 0.0, 1.0, 0.0;  // d/dq of (c, 0, 1 - s); angular about +y
    EXPECT_NEAR((data.jacobian.col(0) - jacobian).norm(), 0.0, kTol);
  }
}

struct PlanarArm {
  double l1 = 1.0, l2 = 0.8, r1 = 0.4, r2 = 0.3, m1 = 3.0, m2 = 2.0, i1 = 0.25, i2 = 0.12;
};

TEST(PlanarTwoLinkTest, MatchesTextbookDynamics) {
  const PlanarArm arm;
  const Model model = load(test_urdfs::planarTwoLink(), {"shoulder", "elbow"}, "tip");
  Data data(model);
  const std::vector<std::array<double, 4>> samples{
      {0.3, -0.7, 1.1, -0.4}, {-1.0, 2.0, 0.0, 2.5}, {2.2, 0.1, -1.5, 0.3}};
  for (const auto& [q1, q2, dq1, dq2] : samples) {
    const std::vector<double> q{q1, q2};
    const std::vector<double> dq{dq1, dq2};
    ASSERT_EQ(update(model, data, q, dq, Quantity::kAll), UpdateStatus::kOk);
    const double c1 = std::cos(q1), s1 = std::sin(q1);
    const double c12 = std::cos(q1 + q2), s12 = std::sin(q1 + q2);
    const double c2 = std::cos(q2), s2 = std::sin(q2);

    const Eigen::Vector3d tip(arm.l1 * c1 + arm.l2 * c12, 0.0, -arm.l1 * s1 - arm.l2 * s12);
    EXPECT_NEAR((data.tip_position - tip).norm(), 0.0, kTol);

    // Potential V = g (m1 z1 + m2 z2) with z1 = -r1 s1, z2 = -l1 s1 - r2 s12.
    EXPECT_NEAR(data.gravity[0],
                -kG * (arm.m1 * arm.r1 * c1 + arm.m2 * (arm.l1 * c1 + arm.r2 * c12)), kTol);
    EXPECT_NEAR(data.gravity[1], -kG * arm.m2 * arm.r2 * c12, kTol);

    const double m11 = arm.i1 + arm.i2 + arm.m1 * arm.r1 * arm.r1 +
                       arm.m2 * (arm.l1 * arm.l1 + arm.r2 * arm.r2 + 2.0 * arm.l1 * arm.r2 * c2);
    const double m12 = arm.i2 + arm.m2 * (arm.r2 * arm.r2 + arm.l1 * arm.r2 * c2);
    const double m22 = arm.i2 + arm.m2 * arm.r2 * arm.r2;
    EXPECT_NEAR(data.mass_matrix(0, 0), m11, kTol);
    EXPECT_NEAR(data.mass_matrix(0, 1), m12, kTol);
    EXPECT_NEAR(data.mass_matrix(1, 0), m12, kTol);
    EXPECT_NEAR(data.mass_matrix(1, 1), m22, kTol);

    const double h = arm.m2 * arm.l1 * arm.r2 * s2;
    EXPECT_NEAR(data.coriolis[0], -h * (2.0 * dq1 * dq2 + dq2 * dq2), kTol);
    EXPECT_NEAR(data.coriolis[1], h * dq1 * dq1, kTol);

    // Linear rows: d(tip)/dq; angular rows: both axes are +y.
    EXPECT_NEAR(data.jacobian(0, 0), -arm.l1 * s1 - arm.l2 * s12, kTol);
    EXPECT_NEAR(data.jacobian(2, 0), -arm.l1 * c1 - arm.l2 * c12, kTol);
    EXPECT_NEAR(data.jacobian(0, 1), -arm.l2 * s12, kTol);
    EXPECT_NEAR(data.jacobian(2, 1), -arm.l2 * c12, kTol);
    EXPECT_NEAR(data.jacobian(4, 0), 1.0, kTol);
    EXPECT_NEAR(data.jacobian(4, 1), 1.0, kTol);
    EXPECT_NEAR(
        data.jacobian.row(1).norm() + data.jacobian.row(3).norm() + data.jacobian.row(5).norm(),
        0.0, kTol);
  }
}

TEST(JointOrderTest, CallerOrderPermutesEveryQuantity) {
  const Model chain_order = load(test_urdfs::planarTwoLink(), {"shoulder", "elbow"}, "tip");
  const Model reversed = load(test_urdfs::planarTwoLink(), {"elbow", "shoulder"}, "tip");
  EXPECT_TRUE(chain_order.jointOrderIsChainOrder());
  EXPECT_FALSE(reversed.jointOrderIsChainOrder());
  EXPECT_EQ(reversed.limits(0).upper, std::numeric_limits<double>::infinity());  // continuous
  EXPECT_EQ(reversed.limits(1).upper, 3.0);
  Data a(chain_order);
  Data b(reversed);
  const std::vector<double> q{0.3, -0.9};
  const std::vector<double> dq{0.5, 1.5};
  const std::vector<double> q_swapped{-0.9, 0.3};
  const std::vector<double> dq_swapped{1.5, 0.5};
  ASSERT_EQ(update(chain_order, a, q, dq, Quantity::kAll), UpdateStatus::kOk);
  ASSERT_EQ(update(reversed, b, q_swapped, dq_swapped, Quantity::kAll), UpdateStatus::kOk);
  EXPECT_NEAR((a.tip_position - b.tip_position).norm(), 0.0, kTol);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(a.gravity[i], b.gravity[1 - i], kTol);
    EXPECT_NEAR(a.coriolis[i], b.coriolis[1 - i], kTol);
    EXPECT_NEAR((a.jacobian.col(i) - b.jacobian.col(1 - i)).norm(), 0.0, kTol);
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(a.mass_matrix(i, j), b.mass_matrix(1 - i, 1 - j), kTol);
    }
  }
}

TEST(ArmatureTest, RotorInertiasAddToTheirOwnDiagonalEntryOnlyInTheCallersOrder) {
  ModelOptions options;
  options.joint_names = {"elbow", "shoulder"};  // not the chain's order
  options.tip_frame = "tip";
  const Model bare = Model::fromUrdfString(test_urdfs::planarTwoLink(), options);
  options.armature = {0.25, 0.75};  // elbow, shoulder [kg m^2]
  const Model geared = Model::fromUrdfString(test_urdfs::planarTwoLink(), options);
  EXPECT_EQ(geared.armature(), options.armature);
  EXPECT_TRUE(bare.armature().empty());
  Data a(bare);
  Data b(geared);
  const std::vector<double> q{-0.9, 0.3};
  const std::vector<double> dq{1.5, 0.5};
  ASSERT_EQ(update(bare, a, q, dq, Quantity::kAll), UpdateStatus::kOk);
  ASSERT_EQ(update(geared, b, q, dq, Quantity::kAll), UpdateStatus::kOk);
  Eigen::Matrix2d added = Eigen::Matrix2d::Zero();
  added.diagonal() << 0.25, 0.75;
  EXPECT_NEAR((b.mass_matrix.topLeftCorner(2, 2) - a.mass_matrix.topLeftCorner(2, 2) - added)
                  .cwiseAbs()
                  .maxCoeff(),
              0.0, kTol);
  // A reflected rotor inertia is driven by its joint's acceleration alone: gravity and the
  // Coriolis and centrifugal torques are the links'.
  EXPECT_NEAR((b.gravity - a.gravity).norm(), 0.0, kTol);
  EXPECT_NEAR((b.coriolis - a.coriolis).norm(), 0.0, kTol);
}

TEST(TcpOffsetTest, OffsetMovesThePointAndKeepsAngularRows) {
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
  tcp.translate(Eigen::Vector3d(0.1, 0.0, 0.2));
  tcp.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  const Model plain = load(test_urdfs::planarTwoLink(), {"shoulder", "elbow"}, "tip");
  const Model with_tcp = load(test_urdfs::planarTwoLink(), {"shoulder", "elbow"}, "tip", tcp);
  Data a(plain);
  Data b(with_tcp);
  const std::vector<double> q{0.4, 0.6};
  ASSERT_EQ(update(plain, a, q, {}, Quantity::kPose | Quantity::kJacobian), UpdateStatus::kOk);
  ASSERT_EQ(update(with_tcp, b, q, {}, Quantity::kPose | Quantity::kJacobian), UpdateStatus::kOk);
  const Eigen::Vector3d expected = a.tip_position + a.tip_rotation * tcp.translation();
  EXPECT_NEAR((b.tip_position - expected).norm(), 0.0, kTol);
  EXPECT_NEAR(((a.tip_rotation * tcp.linear()) - b.tip_rotation).norm(), 0.0, kTol);
  EXPECT_NEAR((a.jacobian.bottomRows<3>() - b.jacobian.bottomRows<3>()).norm(), 0.0, kTol);
  EXPECT_GT((a.jacobian.topRows<3>() - b.jacobian.topRows<3>()).norm(), 0.01);
}

TEST(FoldingTest, FixedChildMassCountsTowardsItsParentBody) {
  // A massive link hung on the tip through a fixed joint must weigh on the joint like a payload.
  std::string urdf = test_urdfs::pendulum();
  urdf.replace(urdf.find("</robot>"), 8,
               R"(<link name="weight"><inertial><mass value="1.0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="tip_to_weight" type="fixed"><parent link="tip"/><child link="weight"/></joint>
</robot>)");
  const Model model = load(urdf, {"hinge"}, "tip");
  Data data(model);
  const std::vector<double> q{0.3};
  ASSERT_EQ(update(model, data, q, {}, Quantity::kGravity | Quantity::kMassMatrix),
            UpdateStatus::kOk);
  EXPECT_NEAR(data.gravity[0], -kG * (2.0 * 0.5 + 1.0 * 1.0) * std::cos(0.3), kTol);
  EXPECT_NEAR(data.mass_matrix(0, 0), 0.52 + 1.0, kTol);
}

TEST(RequestTest, OnlyRequestedQuantitiesAreWritten) {
  const Model model = load(test_urdfs::planarTwoLink(), {"shoulder", "elbow"}, "tip");
  Data data(model);
  data.gravity.setConstant(42.0);
  data.mass_matrix.setConstant(42.0);
  const std::vector<double> q{0.4, 0.6};
  ASSERT_EQ(update(model, data, q, {}, Quantity::kPose), UpdateStatus::kOk);
  EXPECT_EQ(data.computed, Quantity::kPose);
  EXPECT_EQ(data.gravity[0], 42.0);
  EXPECT_EQ(data.mass_matrix(1, 1), 42.0);
}

}  // namespace
}  // namespace comply::model
