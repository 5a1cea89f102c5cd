// The results writer: table.md and results.json come from one description of the columns, so a
// missing value reads "-" (or the column's text) in the table and null in the JSON, units land in
// the headers, and a failing plot script is reported instead of failing the run.

#include "comply/host/plot_script.hpp"
#include "results_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace comply::testing {
namespace {

using experiments::Column;
using experiments::ResultsTable;
using experiments::Value;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ResultsTable trials() {
  ResultsTable table;
  table.columns = {Column("offset_deg", "offset", "deg", 0),
                   Column("seated", "seated"),
                   Column("depth_mm", "depth", "mm", 1),
                   Column("seat_time_s", "seat time", "s", 2).missingAs("never"),
                   Column("failure", "failure"),
                   Column("faults", "faults").jsonOnly()};
  table.rows = {{1.0, true, 20.24, 6.617, Value{}, std::int64_t{0}},
                {6.0, false, 17.16, kNaN, std::string("force_limit"), std::int64_t{2}}};
  return table;
}

TEST(ResultsWriter, MarkdownTableHasUnitsPrecisionAndMissingValues) {
  std::ostringstream out;
  experiments::writeMarkdownTable(trials(), out);
  EXPECT_EQ(out.str(),
            "| offset [deg] | seated | depth [mm] | seat time [s] | failure |\n"
            "|---|---|---|---|---|\n"
            "| 1 | yes | 20.2 | 6.62 | - |\n"
            "| 6 | no | 17.2 | never | force_limit |\n");
}

TEST(ResultsWriter, JsonHasEveryColumnAndNullForMissingValues) {
  const nlohmann::json json = experiments::toJson(trials());
  ASSERT_EQ(json.size(), 2U);
  EXPECT_EQ(json[0]["seated"], true);
  EXPECT_DOUBLE_EQ(json[0]["seat_time_s"].get<double>(), 6.617);
  EXPECT_TRUE(json[0]["failure"].is_null());
  EXPECT_TRUE(json[1]["seat_time_s"].is_null());
  EXPECT_EQ(json[1]["failure"], "force_limit");
  EXPECT_EQ(json[1]["faults"], 2);
}

TEST(ResultsWriter, TransposedTablePutsReferencesBeforeTheResults) {
  ResultsTable table;
  table.transposed = ResultsTable::Transposed{"metric", "condition", {"paper"}};
  table.columns = {Column("condition", "condition"),
                   Column("rms_mm", "RMS", "mm", 1).withReference({"16.3"}),
                   Column("share", "in contact", "share", 3)};
  table.rows = {{std::string("fixed"), 4.84, 1.0}, {std::string("aligned"), 0.52, 0.5}};
  std::ostringstream out;
  experiments::writeMarkdownTable(table, out);
  EXPECT_EQ(out.str(),
            "| metric | paper | fixed | aligned |\n"
            "|---|---|---|---|\n"
            "| RMS [mm] | 16.3 | 4.8 | 0.5 |\n"
            "| in contact [share] | - | 1.000 | 0.500 |\n");
}

TEST(ResultsWriter, WritesBothFiles) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "comply_results_writer_test";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  experiments::writeResults(trials(), folder);
  std::ifstream json_file(folder / "results.json");
  EXPECT_EQ(nlohmann::json::parse(json_file), experiments::toJson(trials()));
  std::ostringstream table;
  experiments::writeMarkdownTable(trials(), table);
  std::ifstream markdown(folder / "table.md");
  std::stringstream written;
  written << markdown.rdbuf();
  EXPECT_EQ(written.str(), table.str());
}

TEST(ResultsWriter, AFailingPlotScriptIsReportedNotThrown) {
  std::ostringstream err;
  EXPECT_FALSE(host::runPlotScript("no_such_plot_script.py", {"a b"}, err));
  EXPECT_NE(err.str().find("warning: no plot"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("no_such_plot_script.py"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace comply::testing
