// `comply experiment output-modes` leaves what docs/output-modes.md quotes: results.json with a
// row per kind of drive, the heavy tool's table and the traces the plot is drawn from.

#include "output_modes/output_modes_experiment.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim_support.hpp"

namespace comply::testing {
namespace {

TEST(OutputModesExperiment, WritesARowPerDriveTheToolTableAndTheTraces) {
  std::ostringstream progress;
  auto options =
      freshExperiment<experiments::OutputModesOptions>("comply_output_modes_test", progress);
  options.modes = {OutputMode::kTorque, OutputMode::kVelocity};
  options.pictures = false;
  std::array<experiments::ToolStepResult, 2> tool;
  const std::vector<experiments::OutputModesRow> rows = experiments::runOutputModes(options, &tool);
  ASSERT_EQ(rows.size(), 2U);

  std::ifstream results_file(options.out_dir / "results.json");
  ASSERT_TRUE(results_file);
  const nlohmann::json results = nlohmann::json::parse(results_file);
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(results[1]["drives"], "velocity");
  EXPECT_DOUBLE_EQ(results[1]["k_z"].get<double>(), rows[1].stiffness.rendered[2]);
  EXPECT_DOUBLE_EQ(results[1]["peak_force_n"].get<double>(), rows[1].contact.peak_n);

  std::ifstream tool_table(options.out_dir / "heavy_tool.md");
  std::stringstream tool_text;
  tool_text << tool_table.rdbuf();
  EXPECT_NE(tool_text.str().find("not declared"), std::string::npos) << tool_text.str();
  for (const char* trace :
       {"contact_torque.csv", "contact_velocity.csv", "tool_declared.csv", "tool_undeclared.csv"}) {
    std::ifstream file(options.out_dir / trace);
    std::string header;
    EXPECT_TRUE(std::getline(file, header)) << trace;
    std::size_t lines = 0;
    for (std::string line; std::getline(file, line);) {
      ++lines;
    }
    EXPECT_GT(lines, 1000U) << trace;
  }
}

}  // namespace
}  // namespace comply::testing
