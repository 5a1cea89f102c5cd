// What the 3D panel is sent: the stiffness ellipsoid, the transforms and markers as JSON, the
// robot description's CDR.

#include "comply/viewer/scene_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

namespace comply::viewer {
namespace {

const Eigen::Quaterniond kTurned45(Eigen::AngleAxisd(std::numbers::pi / 4,
                                                     Eigen::Vector3d::UnitZ()));

TEST(StiffnessEllipsoid, ItsAxesAreTheStiffnessesPrincipalAxesInTheBaseFrame) {
  const Eigen::Matrix3d stiffness = Eigen::Vector3d(1500, 600, 300).asDiagonal();
  const StiffnessEllipsoid ellipsoid = stiffnessEllipsoid(stiffness, kTurned45);
  const Eigen::Matrix3d axes = ellipsoid.orientation.toRotationMatrix();
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
  for (int i = 0; i < 3; ++i) {
    // Each axis has the length of the stiffness along it, and lies along that task axis.
    const Eigen::Vector3d along = axes.col(i);
    const double k = along.dot(kTurned45 * stiffness * kTurned45.inverse() * along);
    EXPECT_NEAR(ellipsoid.lengths_m[i], k * kStiffnessEllipsoidMPerNPerM, 1e-12);
  }
  const Eigen::Index stiffest = [&] {
    Eigen::Index index = 0;
    ellipsoid.lengths_m.maxCoeff(&index);
    return index;
  }();
  EXPECT_NEAR(std::abs(axes.col(stiffest).dot(kTurned45 * Eigen::Vector3d::UnitX())), 1.0, 1e-12);
  EXPECT_NEAR(ellipsoid.lengths_m.maxCoeff(), 0.3, 1e-12);
}

TEST(StiffnessEllipsoid, AFullMatrixComesBackFromItsEllipsoid) {
  Eigen::Matrix3d stiffness;
  stiffness << 900, 200, -100, 200, 500, 50, -100, 50, 400;
  const Eigen::Quaterniond task_frame =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const StiffnessEllipsoid ellipsoid = stiffnessEllipsoid(stiffness, task_frame);
  const Eigen::Matrix3d axes = ellipsoid.orientation.toRotationMatrix();
  const Eigen::Matrix3d rebuilt =
      axes * (ellipsoid.lengths_m / kStiffnessEllipsoidMPerNPerM).asDiagonal() * axes.transpose();
  const Eigen::Matrix3d in_base = task_frame * stiffness * task_frame.inverse();
  EXPECT_LT((rebuilt - in_base).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(StiffnessEllipsoid, ASoftAxisIsStillDrawn) {
  const StiffnessEllipsoid ellipsoid =
      stiffnessEllipsoid(Eigen::Vector3d(0, 0, 2000).asDiagonal(), Eigen::Quaterniond::Identity());
  EXPECT_DOUBLE_EQ(ellipsoid.lengths_m.minCoeff(), kStiffnessEllipsoidMinimumM);
  EXPECT_NEAR(ellipsoid.lengths_m.maxCoeff(), 0.4, 1e-12);
}

TEST(SceneMessages, TransformsCarryTheLinksAndTheExtraFrames) {
  LinkTransform link{"base", "link1", Eigen::Isometry3d::Identity()};
  link.parent_to_child.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
  link.parent_to_child.linear() = kTurned45.toRotationMatrix();
  const auto message = nlohmann::json::parse(frameTransformsJson(
      1'500'000'002, {link}, {{"base", "comply/task_frame", Eigen::Vector3d(1, 2, 3), kTurned45}}));
  ASSERT_EQ(message["transforms"].size(), 2U);
  const auto& first = message["transforms"][0];
  EXPECT_EQ(first["timestamp"]["sec"], 1);
  EXPECT_EQ(first["timestamp"]["nsec"], 500'000'002);
  EXPECT_EQ(first["parent_frame_id"], "base");
  EXPECT_EQ(first["child_frame_id"], "link1");
  EXPECT_DOUBLE_EQ(first["translation"]["z"].get<double>(), 0.3);
  EXPECT_NEAR(first["rotation"]["z"].get<double>(), std::sin(std::numbers::pi / 8), 1e-15);
  EXPECT_EQ(message["transforms"][1]["child_frame_id"], "comply/task_frame");
}

TEST(SceneMessages, TheForceArrowPointsAlongTheForceAndShowsOnlyAContact) {
  ArmMarkers markers;
  markers.frame_id = "base";
  markers.tcp_position = Eigen::Vector3d(0.4, 0, 0.3);
  markers.contact_force = Eigen::Vector3d(0, 0, 0.4);
  auto update = nlohmann::json::parse(sceneUpdateJson(0, markers));
  ASSERT_EQ(update["entities"].size(), 3U);
  EXPECT_EQ(update["entities"][1]["id"], "contact_force");
  EXPECT_TRUE(update["entities"][1]["arrows"].empty()) << "0.4 N draws no arrow";
  EXPECT_TRUE(update["entities"][0]["spheres"].empty()) << "joint control: no ellipsoid";
  markers.contact_force = Eigen::Vector3d(0, 0, -20);
  update = nlohmann::json::parse(sceneUpdateJson(0, markers));
  const auto& arrow = update["entities"][1]["arrows"][0];
  const auto& q = arrow["pose"]["orientation"];
  const Eigen::Quaterniond orientation(q["w"], q["x"], q["y"], q["z"]);
  EXPECT_LT((orientation * Eigen::Vector3d::UnitX() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  EXPECT_NEAR(arrow["shaft_length"].get<double>() + arrow["head_length"].get<double>(), 0.2, 1e-12);
  markers.contact_force = Eigen::Vector3d(500, 0, 0);
  update = nlohmann::json::parse(sceneUpdateJson(0, markers));
  const auto& long_arrow = update["entities"][1]["arrows"][0];
  EXPECT_NEAR(long_arrow["shaft_length"].get<double>() + long_arrow["head_length"].get<double>(),
              kForceArrowMaximumM, 1e-12);
}

TEST(SceneMessages, TheChunkPathIsALineStripThroughItsWaypoints) {
  ArmMarkers markers;
  markers.frame_id = "base";
  markers.path = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0),
                  Eigen::Vector3d(0.1, 0.1, 0)};
  const auto update = nlohmann::json::parse(sceneUpdateJson(0, markers));
  const auto& line = update["entities"][2]["lines"][0];
  EXPECT_EQ(line["type"], 0);
  ASSERT_EQ(line["points"].size(), 3U);
  EXPECT_DOUBLE_EQ(line["points"][2]["y"].get<double>(), 0.1);
  EXPECT_EQ(update["entities"][2]["frame_id"], "base");
}

TEST(SceneMessages, SchemasAreJsonSchemasNamedForFoxglove) {
  const auto transforms = nlohmann::json::parse(frameTransformsSchema());
  EXPECT_EQ(transforms["title"], "foxglove.FrameTransforms");
  EXPECT_EQ(transforms["properties"]["transforms"]["type"], "array");
  const auto scene = nlohmann::json::parse(sceneUpdateSchema());
  EXPECT_EQ(scene["title"], "foxglove.SceneUpdate");
  EXPECT_TRUE(scene["properties"]["entities"]["items"]["properties"].contains("spheres"));
}

TEST(SceneMessages, AStringMessageIsItsCdrBytes) {
  EXPECT_EQ(stringMessageCdr("ab"),
            (std::vector<std::uint8_t>{0, 1, 0, 0, 3, 0, 0, 0, 'a', 'b', 0}));
  EXPECT_EQ(stringMessageCdr(""), (std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0, 0, 0, 0}));
}

}  // namespace
}  // namespace comply::viewer
