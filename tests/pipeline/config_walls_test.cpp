// The controller file's walls: and boxes: lists (config_walls.cpp): read as written, renormalised
// within a tolerance, and each bad entry refused with its own name in the error.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "comply/pipeline/config.hpp"
#include "config_errors.hpp"

namespace comply::pipeline {
namespace {

WrapperConfig parse(const std::string& lines) {
  return parseWrapperText(
      "arm_controller:\n  ros__parameters:\n    plugin: cartesian_impedance\n    robot: fr3\n" +
          lines,
      "arm.yaml");
}

void expectError(const std::string& lines, const std::vector<std::string>& fragments) {
  test::expectReadError(parse, lines, fragments);
}

TEST(WallConfig, NoneByDefaultWithTheDocumentedGains) {
  const WrapperConfig config = parse("");
  EXPECT_FALSE(config.walls.any());
  EXPECT_DOUBLE_EQ(config.walls.brake_distance_m, 0.05);
  EXPECT_DOUBLE_EQ(config.walls.stiffness_n_per_m, 2000.0);
  EXPECT_DOUBLE_EQ(config.walls.damping_n_s_per_m, 200.0);
}

TEST(WallConfig, WallsBoxesAndGainsAreReadAsWritten) {
  const WrapperConfig config = parse(
      "    walls:\n"
      "      - {point: [0.6, 0.0, 0.0], normal: [1.0, 0.0, 0.0]}\n"
      "      - {point: [0.0, 0.0, 0.1], normal: [0.0, 0.7071, -0.7071]}\n"
      "    boxes:\n"
      "      - {min: [0.2, -0.4, 0.05], max: [0.7, 0.4, 0.8]}\n"
      "    wall:\n      brake_distance_m: 0.03\n      stiffness_n_per_m: 500\n"
      "      damping_n_s_per_m: 150\n");
  ASSERT_EQ(config.walls.planes.size(), 2U);
  EXPECT_EQ(config.walls.planes[0].point, Eigen::Vector3d(0.6, 0.0, 0.0));
  EXPECT_EQ(config.walls.planes[0].normal, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_NEAR(config.walls.planes[1].normal.norm(), 1.0, 1e-15);  // renormalised
  ASSERT_EQ(config.walls.boxes.size(), 1U);
  EXPECT_EQ(config.walls.boxes[0].min, Eigen::Vector3d(0.2, -0.4, 0.05));
  EXPECT_EQ(config.walls.boxes[0].max, Eigen::Vector3d(0.7, 0.4, 0.8));
  EXPECT_DOUBLE_EQ(config.walls.brake_distance_m, 0.03);
  EXPECT_DOUBLE_EQ(config.walls.stiffness_n_per_m, 500.0);
  EXPECT_DOUBLE_EQ(config.walls.damping_n_s_per_m, 150.0);
}

TEST(WallConfig, EachBadEntryIsNamed) {
  const std::string prefix = "arm_controller.ros__parameters.";
  expectError(
      "    walls:\n      - {point: [0, 0, 0], normal: [1, 0, 0]}\n"
      "      - {point: [0, 0, 0], normal: [0, 0, 0]}\n",
      {prefix + "walls[1].normal", "must not be zero"});
  expectError("    walls:\n      - {point: [0, 0, 0], normal: [0, 2, 0]}\n",
              {prefix + "walls[0].normal", "unit vector", "2.0"});
  expectError("    walls:\n      - {point: [0, .nan, 0], normal: [0, 0, 1]}\n",
              {prefix + "walls[0].point", "finite"});
  expectError("    walls:\n      - {point: [0, 0], normal: [0, 0, 1]}\n",
              {prefix + "walls[0].point", "[x, y, z]"});
  expectError("    walls:\n      - {normal: [0, 0, 1]}\n", {prefix + "walls[0].point", "required"});
  expectError("    walls:\n      - {point: [0, 0, 0], normal: [0, 0, 1], side: in}\n",
              {prefix + "walls[0].side", "not a known key"});
  expectError("    walls: {point: [0, 0, 0]}\n", {prefix + "walls", "must be a list"});
  expectError("    boxes:\n      - {min: [0.2, 0.5, 0], max: [0.7, 0.4, 0.8]}\n",
              {prefix + "boxes[0].min", "below max"});
  expectError("    boxes:\n      - {min: [0, 0, 0], max: [1, .inf, 1]}\n",
              {prefix + "boxes[0].max", "finite"});
  expectError("    wall:\n      brake_distance_m: 0\n", {prefix + "wall.brake_distance_m"});
  std::string many = "    boxes:\n";
  for (int i = 0; i < kMaxWallPlanes / 6 + 1; ++i) {
    many += "      - {min: [0, 0, 0], max: [1, 1, 1]}\n";
  }
  expectError(many, {prefix + "walls", "more than 48 planes"});
}

}  // namespace
}  // namespace comply::pipeline
