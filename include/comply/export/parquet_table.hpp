#pragma once
// A table written as one Apache Parquet file, the format LeRobot datasets keep their frames and
// episode metadata in. Debian has no Arrow or Parquet library, so comply writes the subset its
// datasets need itself, from the format's specification:
//
//   columns   INT64, FLOAT, DOUBLE, UTF-8 strings (BYTE_ARRAY, logical type STRING), all
//             required; and lists of a fixed number of FLOATs per row (the standard three-level
//             LIST: a required group, a repeated group `list`, a required `element`), which is
//             how a vector feature (a state, an action, a stiffness) is stored
//   layout    row groups of at most row_group_rows rows, one data page (v1) per column chunk,
//             PLAIN values, RLE repetition and definition levels, no compression, no
//             dictionary, no statistics; key/value metadata in the footer
//
// Any Parquet reader reads it (tests: hyparquet, independent of this code). Not real-time: a
// tool's output, built in memory and written once.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace comply::exporter {

class ThriftCompactWriter;

class ParquetTable {
 public:
  /// Columns in the order they are added. Every column has the table's rows (the first column
  /// sets them); a name may appear once. Throws std::invalid_argument naming the column otherwise.
  void addInt64(const std::string& name, std::vector<std::int64_t> values);
  void addFloat(const std::string& name, std::vector<float> values);
  void addDouble(const std::string& name, std::vector<double> values);
  void addString(const std::string& name, std::vector<std::string> values);
  /// `width` floats per row, row after row (values.size() = rows x width, width >= 1).
  void addFloatList(const std::string& name, std::vector<float> values, int width);
  /// The rows of `other` after these: the same columns in the same order (names, kinds, list
  /// widths), else std::invalid_argument naming the first that differs.
  void append(const ParquetTable& other);
  /// A key/value pair in the file's footer.
  void addMetadata(const std::string& key, const std::string& value);

  /// A numeric column as stored (INT64 in `int64s`, FLOAT and FLOAT lists in `floats`, DOUBLE in
  /// `doubles`; `width` values per row), for what is computed from a table (its statistics).
  struct NumericColumn {
    std::string_view name;
    int width;
    std::span<const std::int64_t> int64s;
    std::span<const float> floats;
    std::span<const double> doubles;
  };
  /// Every column but the strings, in order; valid while the table is not changed.
  [[nodiscard]] std::vector<NumericColumn> numericColumns() const;

  [[nodiscard]] std::int64_t rows() const noexcept { return rows_; }
  [[nodiscard]] std::size_t columns() const noexcept { return columns_.size(); }

  /// The file's bytes: row groups of at most `row_group_rows` rows (>= 1).
  [[nodiscard]] std::vector<std::uint8_t> serialize(std::int64_t row_group_rows = 1 << 16) const;
  /// serialize() into `path` (replaced). Throws std::runtime_error naming the path when it cannot.
  void write(const std::filesystem::path& path, std::int64_t row_group_rows = 1 << 16) const;

 private:
  enum class Kind : std::uint8_t { kInt64, kFloat, kDouble, kString, kFloatList };
  struct Column {
    std::string name;
    Kind kind;
    int width = 1;  // values per row (lists)
    std::vector<std::int64_t> int64s = {};
    std::vector<float> floats = {};
    std::vector<double> doubles = {};
    std::vector<std::string> strings = {};
  };
  /// Where a column chunk's page landed in the file, for the footer.
  struct ChunkPlace {
    std::int64_t offset;
    std::int64_t size;
    std::int64_t values;
  };
  void add(Column column, std::int64_t column_rows);
  static std::int32_t physicalType(Kind kind) noexcept;
  /// Rows [first, first + count) of `column` as one data page with its header; `values`: the
  /// leaf values in it.
  static std::vector<std::uint8_t> encodePage(const Column& column, std::int64_t first,
                                              std::int64_t count, std::int64_t& values);
  void encodeSchema(ThriftCompactWriter& thrift) const;
  void encodeRowGroup(ThriftCompactWriter& thrift, const std::vector<ChunkPlace>& chunks,
                      std::int64_t rows) const;

  std::vector<Column> columns_;
  std::vector<std::pair<std::string, std::string>> metadata_;
  std::int64_t rows_ = 0;  // set by the first column
};

}  // namespace comply::exporter
