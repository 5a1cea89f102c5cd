// The cross-platform check: one plugin, one controller file, one command; four robots reach the
// common target within 2 mm / 1 deg. Also checks what the experiment leaves behind: results.json
// with a row per robot, and a side-by-side picture that actually shows robots.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "comply/model/robot_description.hpp"
#include "comply/sim/image.hpp"
#include "cross_platform/cross_platform_experiment.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

TEST(CrossPlatform, EveryRobotReachesTheCommonTargetAndThePicturesShowThem) {
  std::ostringstream progress;
  auto options =
      freshExperiment<experiments::CrossPlatformOptions>("comply_cross_platform_test", progress);
  const std::vector<experiments::CrossPlatformRow> rows = experiments::runCrossPlatform(options);

  // Every robot on the search path (the four of the paper, and any added as a folder), in order.
  const std::vector<std::string> robots = model::availableRobots();
  ASSERT_GE(robots.size(), 4U);
  // Then the UR5e again with each other kind of drive.
  ASSERT_EQ(rows.size(), robots.size() + options.other_modes.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const experiments::CrossPlatformRow& row = rows[i];
    SCOPED_TRACE(row.robot + " " + std::string(toString(row.output)));
    if (i < robots.size()) {
      EXPECT_EQ(row.robot, robots[i]);
      EXPECT_EQ(row.output, OutputMode::kTorque);
    } else {
      EXPECT_EQ(row.robot, "ur5e");
      EXPECT_EQ(row.output, options.other_modes[i - robots.size()]);
    }
    EXPECT_EQ(row.dof, static_cast<int>(model::loadRobotDescription(row.robot).joints.size()));
    EXPECT_LT(row.position_error_mm, 2.0);
    EXPECT_LT(row.orientation_error_deg, 1.0);
    EXPECT_FALSE(std::isnan(row.settle_time_s));
    // A law ran: in admittance the torque is the virtual arm's, which carries no weight and
    // follows a reference that starts and ends at rest.
    EXPECT_GT(row.peak_torque_nm, isAdmittance(row.output) ? 0.01 : 1.0);
    EXPECT_EQ(row.rejections, 0U);
    EXPECT_EQ(row.faults, 0U);
  }

  std::ifstream results_file(options.out_dir / "results.json");
  ASSERT_TRUE(results_file);
  const nlohmann::json results = nlohmann::json::parse(results_file);
  ASSERT_TRUE(results.is_array());
  ASSERT_EQ(results.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(results[i]["robot"], rows[i].robot);
    EXPECT_EQ(results[i]["output"], toString(rows[i].output));
    EXPECT_DOUBLE_EQ(results[i]["position_error_mm"].get<double>(), rows[i].position_error_mm);
  }

  // Side by side: one 640 x 480 frame per robot (torque-driven) with 8 px gaps.
  const sim::Image combined = sim::readPng(options.out_dir / "cross_platform.png");
  const auto frames = static_cast<int>(robots.size());
  EXPECT_EQ(combined.width, frames * 640 + (frames - 1) * 8);
  EXPECT_EQ(combined.height, 480);
  // Each robot's frame is mostly not sky, and the robot moved between start and end.
  for (const std::string robot : {"fr3", "ur5e"}) {
    SCOPED_TRACE(robot);
    const sim::Image start = sim::readPng(options.out_dir / robot / "start.png");
    const sim::Image end = sim::readPng(options.out_dir / robot / "end.png");
    const std::array<std::uint8_t, 3> sky = {end.rgb[0], end.rgb[1], end.rgb[2]};
    const double not_sky = sim::fractionDifferentFrom(end, sky, 12);
    EXPECT_GT(not_sky, 0.3);
    EXPECT_LT(not_sky, 0.95);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < end.rgb.size(); i += 3) {
      changed += std::abs(int(end.rgb[i]) - int(start.rgb[i])) > 24 ? 1 : 0;
    }
    EXPECT_GT(static_cast<double>(changed) / (end.width * end.height), 0.005);
  }
}

}  // namespace
}  // namespace comply::testing
