// The Parquet writer (parquet_table.hpp): what it refuses, the file's frame, and every kind of
// column read back by hyparquet (tests/export/read_parquet.mjs), a reader written independently
// of this code, value for value, across row groups.

#include "comply/export/parquet_table.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "read_parquet.hpp"
#include "scratch.hpp"

namespace comply::exporter {
namespace {

using test::readWithHyparquet;

template <typename Call>
void expectRefusal(Call call, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "accepted; expected a refusal naming: " << fragment;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(ParquetTable, RefusesColumnsOfAnotherLengthTwiceTheSameNameAndListsOfNoWidth) {
  ParquetTable table;
  table.addInt64("frame_index", {0, 1, 2});
  expectRefusal(
      [&] {
        table.addFloat("timestamp", {0.0F, 0.1F});
      },
      "column 'timestamp' has 2 rows, the table 3 (column 'frame_index')");
  expectRefusal(
      [&] {
        table.addDouble("frame_index", {0.0, 1.0, 2.0});
      },
      "column 'frame_index' added twice");
  expectRefusal(
      [&] {
        table.addFloatList("action", {1.0F, 2.0F, 3.0F}, 0);
      },
      "column 'action' needs a width of at least 1");
  expectRefusal(
      [&] {
        table.addFloatList("action", {1.0F, 2.0F, 3.0F, 4.0F}, 3);
      },
      "column 'action' has 4 values, not a multiple of its width 3");
  expectRefusal([&] { table.addString("", {"a", "b", "c"}); }, "a column needs a name");
  // What was refused left the table as it was.
  EXPECT_EQ(table.columns(), 1U);
  EXPECT_EQ(table.rows(), 3);
  EXPECT_THROW((void)table.serialize(0), std::invalid_argument);
}

TEST(ParquetTable, TheFileIsFramedByItsMagicAndTheFootersLength) {
  ParquetTable table;
  table.addDouble("x", {1.0, 2.0});
  const std::vector<std::uint8_t> bytes = table.serialize();
  ASSERT_GT(bytes.size(), 12U);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "PAR1");
  EXPECT_EQ(std::string(bytes.end() - 4, bytes.end()), "PAR1");
  std::uint32_t footer = 0;
  std::memcpy(&footer, bytes.data() + bytes.size() - 8, 4);
  // Magic, one page (its header, two doubles), the footer, its length, magic.
  EXPECT_LT(footer, bytes.size() - 8 - 4 - 16);
  EXPECT_GT(footer, 0U);
}

TEST(ParquetTable, EveryKindOfColumnReadsBackInAnIndependentReaderAcrossRowGroups) {
  const testing::ScratchDir scratch("parquet");
  const std::filesystem::path path = scratch.path() / "frames.parquet";
  constexpr int kRows = 7;
  std::vector<std::int64_t> index;
  std::vector<float> timestamp;
  std::vector<double> energy;
  std::vector<std::string> task;
  std::vector<float> state;  // three per row
  for (int i = 0; i < kRows; ++i) {
    index.push_back(i == 6 ? std::numeric_limits<std::int64_t>::min()
                           : (std::int64_t{1} << 53) + i);
    timestamp.push_back(static_cast<float>(i) /
                        30.0F);  // not exact in binary: compared bit for bit
    energy.push_back(1.0 / (i + 1));
    task.push_back(i % 2 == 0 ? "press on the table" : (i == 3 ? "" : "steife Fläche, 30°"));
    for (int k = 0; k < 3; ++k) {
      state.push_back(static_cast<float>(0.1 * i - 0.01 * k));
    }
  }
  ParquetTable table;
  table.addInt64("index", index);
  table.addFloat("timestamp", timestamp);
  table.addDouble("energy", energy);
  table.addString("task", task);
  table.addFloatList("observation.state", state, 3);
  table.addMetadata("comply", "{\"fps\": 30}");
  table.write(path, /*row_group_rows=*/3);

  const nlohmann::json read = readWithHyparquet(path);
  ASSERT_FALSE(read.is_null());
  EXPECT_EQ(read["num_rows"], kRows);
  EXPECT_EQ(read["row_groups"], nlohmann::json::array({3, 3, 1}));
  EXPECT_EQ(read["created_by"], "comply");
  EXPECT_EQ(read["key_value_metadata"]["comply"], "{\"fps\": 30}");
  const nlohmann::json& leaves = read["leaves"];
  ASSERT_EQ(leaves.size(), 5U);
  EXPECT_EQ(leaves[0]["type"], "INT64");
  EXPECT_EQ(leaves[1]["type"], "FLOAT");
  EXPECT_EQ(leaves[2]["type"], "DOUBLE");
  EXPECT_EQ(leaves[3]["type"], "BYTE_ARRAY");
  EXPECT_EQ(leaves[4]["name"], "element");
  EXPECT_EQ(leaves[4]["type"], "FLOAT");
  const nlohmann::json& rows = read["rows"];
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kRows));
  for (int i = 0; i < kRows; ++i) {
    const nlohmann::json& row = rows[static_cast<std::size_t>(i)];
    EXPECT_EQ(row["index"].get<std::string>(), std::to_string(index[static_cast<std::size_t>(i)]));
    EXPECT_EQ(static_cast<float>(row["timestamp"].get<double>()), timestamp[i]) << i;
    EXPECT_EQ(row["energy"].get<double>(), energy[static_cast<std::size_t>(i)]) << i;
    EXPECT_EQ(row["task"].get<std::string>(), task[static_cast<std::size_t>(i)]) << i;
    const nlohmann::json& vector = row["observation.state"];
    ASSERT_EQ(vector.size(), 3U) << i;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(static_cast<float>(vector[static_cast<std::size_t>(k)].get<double>()),
                state[static_cast<std::size_t>(3 * i + k)])
          << i << ", " << k;
    }
  }
}

TEST(ParquetTable, AnEmptyTableIsAValidFileOfNoRows) {
  const testing::ScratchDir scratch("parquet_empty");
  const std::filesystem::path path = scratch.path() / "empty.parquet";
  ParquetTable table;
  table.addInt64("index", {});
  table.addFloatList("action", {}, 7);
  table.write(path);
  const nlohmann::json read = readWithHyparquet(path);
  ASSERT_FALSE(read.is_null());
  EXPECT_EQ(read["num_rows"], 0);
  EXPECT_TRUE(read["rows"].empty());
}

TEST(ParquetTable, AnUnwritablePathIsNamedInTheError) {
  ParquetTable table;
  table.addInt64("index", {1});
  try {
    table.write("/nonexistent-folder/frames.parquet");
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent-folder/frames.parquet"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace comply::exporter
