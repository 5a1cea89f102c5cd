// A task file's `path` block streams commands with a task frame from the path: the probe draws an
// S on the table in the Darboux frame of the path on the table top, pressing with
// 200 N/m x 30 mm = 6 N along the table normal while following the S stiffly in the plane.

#include <gtest/gtest.h>

#include "comply/host/sim_session.hpp"
#include "comply/task/path.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

TEST(TaskPath, ProbeFollowsTheSOnTheTableAndPressesWithStiffnessTimesOffset) {
  host::SimRunOptions run = fr3ExampleRun("path_on_table.yaml");
  ASSERT_TRUE(run.task.path_points);
  const task::Path path(*run.task.path_points);
  const double start = run.task.path_options.start_time_s;
  const double end = start + path.length() / run.task.path_options.speed_m_per_s;
  const host::SimResult result = host::runSimulation(run);
  ASSERT_EQ(result.summary.faults, 0U);
  ASSERT_EQ(result.summary.rejections, 0U);

  double force_sum = 0.0;
  std::size_t count = 0;
  double worst_in_plane_m = 0.0;
  double worst_height_m = 0.0;
  for (std::size_t row = 0; row < result.log.size(); ++row) {
    const double t = result.log.time_s[row];
    if (t < start + 0.5 || t > end) {
      continue;  // skip the first contact
    }
    const Eigen::Vector3d tcp = result.log.tcp_position[row];
    double closest = 1.0;
    for (double s = 0.0; s <= path.length(); s += 5e-4) {
      closest = std::min(closest, (tcp - path.position(s)).head<2>().norm());
    }
    worst_in_plane_m = std::max(worst_in_plane_m, closest);
    worst_height_m = std::max(worst_height_m, std::abs(tcp.z() - 0.41));
    force_sum += result.log.contact_wrench[row][2];
    ++count;
  }
  ASSERT_GT(count, 1000U);
  // Budget: table friction (0.3 x 6 N) plus the FR3 plant's joint friction (about 1 N m per
  // joint, uncompensated here) against 1000 N/m in the plane: below 10 mm off the S.
  EXPECT_LT(worst_in_plane_m, 0.010);
  EXPECT_LT(worst_height_m, 0.002);  // on the table, not through it
  EXPECT_NEAR(force_sum / static_cast<double>(count), 200.0 * 0.03, 0.25 * 6.0);
}

TEST(TaskPath, BadPathBlocksAreNamed) {
  const auto fails_with = [](const std::string& path_block, const std::string& expected) {
    try {
      (void)host::parseTaskFile("task:\n  waypoints: [{time_s: 0.0}]\n  path:\n" + path_block,
                                "test", kSourceDir, true, 7);
      ADD_FAILURE() << "accepted: " << path_block;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  };
  fails_with("    start_time_s: 1.0\n    frame: darboux\n    points: [[0, 0, 0], [0.1, 0, 0]]\n",
             "surface_normal");
  fails_with("    start_time_s: 1.0\n    points: [[0, 0, 0]]\n", "at least two");
  fails_with("    start_time_s: 1.0\n    points: [[0, 0, 0], [0, 0, 0]]\n", "zero");
  fails_with("    start_time_s: 1.0\n    points: [[0, 0, 0], [0.1, 0, 0]]\n    frame: helix\n",
             "frenet, darboux or fixed");
  fails_with("    start_time_s: 1.0\n    points: [[0.4, 0, 0.4], [0.4, 30485, 0.4]]\n",
             "task.path.points: Path of 30485 m would need");
  EXPECT_THROW((void)host::parseTaskFile(
                   "task:\n  waypoints: [{time_s: 0.0}]\n  path: {start_time_s: 0, points: "
                   "[[0, 0, 0], [0.1, 0, 0]]}\n",
                   "test", kSourceDir, false, 7),
               std::runtime_error);  // joint controller
}

TEST(TaskFile, SizesAndDurationsAreBounded) {
  const auto fails_with = [](const std::string& yaml, const std::string& expected) {
    try {
      (void)host::parseTaskFile(yaml, "test", kSourceDir, true, 7);
      ADD_FAILURE() << "accepted: " << yaml.substr(0, 80);
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  };
  fails_with("task:\n  duration_s: 1.0e6\n  waypoints: [{time_s: 0.0}]\n", "at most 600 s");
  fails_with("task:\n  duration_s: .inf\n  waypoints: [{time_s: 0.0}]\n", "not a finite number");
  std::string many = "task:\n  waypoints:\n";
  for (int i = 0; i <= 100'000; ++i) {
    many += "    - {time_s: 0.0}\n";
  }
  fails_with(many, "more than 100000");
}

}  // namespace
}  // namespace comply::testing
