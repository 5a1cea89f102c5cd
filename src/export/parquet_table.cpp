// Parquet's file layout (see parquet_table.hpp): "PAR1", for each row group the pages of its
// column chunks, the footer (FileMetaData, Thrift compact), its length, "PAR1".

#include "comply/export/parquet_table.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "thrift_compact.hpp"

namespace comply::exporter {
namespace {

using Thrift = ThriftCompactWriter;
using Bytes = std::vector<std::uint8_t>;

// Enumerations of the format (parquet.thrift).
constexpr std::int32_t kTypeInt64 = 2;
constexpr std::int32_t kTypeFloat = 4;
constexpr std::int32_t kTypeDouble = 5;
constexpr std::int32_t kTypeByteArray = 6;
constexpr std::int32_t kRequired = 0;
constexpr std::int32_t kRepeated = 2;
constexpr std::int32_t kConvertedUtf8 = 0;
constexpr std::int32_t kConvertedList = 3;
constexpr std::int32_t kEncodingPlain = 0;
constexpr std::int32_t kEncodingRle = 3;
constexpr std::int32_t kCodecUncompressed = 0;
constexpr std::int32_t kPageData = 0;
constexpr std::int16_t kLogicalString = 1;  // LogicalType's union members
constexpr std::int16_t kLogicalList = 3;

template <typename T>
void appendLittleEndian(Bytes& out, T value) {
  static_assert(std::endian::native == std::endian::little, "a little-endian host");
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

/// Levels in the RLE / bit-packed hybrid at bit width 1, as runs of equal values, behind the
/// 4-byte length a v1 data page puts before them.
void appendLevels(Bytes& out, const std::vector<std::uint8_t>& levels) {
  Bytes runs;
  std::size_t i = 0;
  while (i < levels.size()) {
    std::size_t end = i;
    while (end < levels.size() && levels[end] == levels[i]) {
      ++end;
    }
    std::uint64_t header = static_cast<std::uint64_t>(end - i) << 1;  // low bit 0: an RLE run
    while (header >= 0x80) {
      runs.push_back(static_cast<std::uint8_t>(header | 0x80));
      header >>= 7;
    }
    runs.push_back(static_cast<std::uint8_t>(header));
    runs.push_back(levels[i]);  // the value, in one byte at bit width 1
    i = end;
  }
  appendLittleEndian(out, static_cast<std::uint32_t>(runs.size()));
  out.insert(out.end(), runs.begin(), runs.end());
}

std::int32_t checkedSize(std::size_t size, const std::string& what) {
  if (size > static_cast<std::size_t>(INT32_MAX)) {
    throw std::length_error("parquet: " + what + " is larger than a page may be (2 GiB)");
  }
  return static_cast<std::int32_t>(size);
}

}  // namespace

std::int32_t ParquetTable::physicalType(Kind kind) noexcept {
  switch (kind) {
    case Kind::kInt64:
      return kTypeInt64;
    case Kind::kDouble:
      return kTypeDouble;
    case Kind::kString:
      return kTypeByteArray;
    case Kind::kFloat:
    case Kind::kFloatList:
      break;
  }
  return kTypeFloat;
}

void ParquetTable::add(Column column, std::int64_t column_rows) {
  for (const Column& existing : columns_) {
    if (existing.name == column.name) {
      throw std::invalid_argument("parquet: column '" + column.name + "' added twice");
    }
  }
  if (column.name.empty()) {
    throw std::invalid_argument("parquet: a column needs a name");
  }
  if (!columns_.empty() && column_rows != rows_) {
    throw std::invalid_argument(
        "parquet: column '" + column.name + "' has " + std::to_string(column_rows) +
        " rows, the table " + std::to_string(rows_) + " (column '" + columns_.front().name + "')");
  }
  rows_ = column_rows;
  columns_.push_back(std::move(column));
}

void ParquetTable::addInt64(const std::string& name, std::vector<std::int64_t> values) {
  const auto rows = static_cast<std::int64_t>(values.size());
  add({.name = name, .kind = Kind::kInt64, .int64s = std::move(values)}, rows);
}

void ParquetTable::addFloat(const std::string& name, std::vector<float> values) {
  const auto rows = static_cast<std::int64_t>(values.size());
  add({.name = name, .kind = Kind::kFloat, .floats = std::move(values)}, rows);
}

void ParquetTable::addDouble(const std::string& name, std::vector<double> values) {
  const auto rows = static_cast<std::int64_t>(values.size());
  add({.name = name, .kind = Kind::kDouble, .doubles = std::move(values)}, rows);
}

void ParquetTable::addString(const std::string& name, std::vector<std::string> values) {
  const auto rows = static_cast<std::int64_t>(values.size());
  add({.name = name, .kind = Kind::kString, .strings = std::move(values)}, rows);
}

void ParquetTable::addFloatList(const std::string& name, std::vector<float> values, int width) {
  if (width < 1) {
    throw std::invalid_argument("parquet: column '" + name + "' needs a width of at least 1");
  }
  if (values.size() % static_cast<std::size_t>(width) != 0) {
    throw std::invalid_argument("parquet: column '" + name + "' has " +
                                std::to_string(values.size()) + " values, not a multiple of " +
                                "its width " + std::to_string(width));
  }
  const auto rows = static_cast<std::int64_t>(values.size() / static_cast<std::size_t>(width));
  add({.name = name, .kind = Kind::kFloatList, .width = width, .floats = std::move(values)}, rows);
}

void ParquetTable::append(const ParquetTable& other) {
  if (other.columns_.size() != columns_.size()) {
    throw std::invalid_argument("parquet: appending " + std::to_string(other.columns_.size()) +
                                " columns to " + std::to_string(columns_.size()));
  }
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const Column& mine = columns_[c];
    const Column& theirs = other.columns_[c];
    if (mine.name != theirs.name || mine.kind != theirs.kind || mine.width != theirs.width) {
      throw std::invalid_argument("parquet: appending column '" + theirs.name + "' onto '" +
                                  mine.name + "' (another name, kind or width)");
    }
  }
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    Column& mine = columns_[c];
    const Column& theirs = other.columns_[c];
    mine.int64s.insert(mine.int64s.end(), theirs.int64s.begin(), theirs.int64s.end());
    mine.floats.insert(mine.floats.end(), theirs.floats.begin(), theirs.floats.end());
    mine.doubles.insert(mine.doubles.end(), theirs.doubles.begin(), theirs.doubles.end());
    mine.strings.insert(mine.strings.end(), theirs.strings.begin(), theirs.strings.end());
  }
  rows_ += other.rows_;
}

void ParquetTable::addMetadata(const std::string& key, const std::string& value) {
  metadata_.emplace_back(key, value);
}

std::vector<std::uint8_t> ParquetTable::encodePage(const Column& column, std::int64_t first,
                                                   std::int64_t count, std::int64_t& values) {
  Bytes page;
  values = count;
  const auto begin = static_cast<std::size_t>(first);
  const auto end = static_cast<std::size_t>(first + count);
  const auto plain = [&](const auto& source, std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i) {
      appendLittleEndian(page, source[i]);
    }
  };
  switch (column.kind) {
    case Kind::kInt64:
      plain(column.int64s, begin, end);
      break;
    case Kind::kFloat:
      plain(column.floats, begin, end);
      break;
    case Kind::kDouble:
      plain(column.doubles, begin, end);
      break;
    case Kind::kString:
      for (std::size_t i = begin; i < end; ++i) {
        const std::string& text = column.strings[i];
        appendLittleEndian(page, static_cast<std::uint32_t>(checkedSize(text.size(), column.name)));
        page.insert(page.end(), text.begin(), text.end());
      }
      break;
    case Kind::kFloatList: {
      const auto width = static_cast<std::size_t>(column.width);
      values = count * column.width;
      // A new row starts at repetition level 0, its other elements repeat at 1; every element is
      // present, at the definition level of the repeated group (1).
      std::vector<std::uint8_t> repetition(static_cast<std::size_t>(values), 1);
      for (std::size_t row = 0; row < static_cast<std::size_t>(count); ++row) {
        repetition[row * width] = 0;
      }
      appendLevels(page, repetition);
      appendLevels(page, std::vector<std::uint8_t>(static_cast<std::size_t>(values), 1));
      plain(column.floats, begin * width, end * width);
      break;
    }
  }
  Bytes header;
  Thrift thrift(header);
  thrift.beginStruct();  // PageHeader
  thrift.fieldI32(1, kPageData);
  thrift.fieldI32(2, checkedSize(page.size(), column.name));
  thrift.fieldI32(3, checkedSize(page.size(), column.name));
  thrift.fieldStruct(5);  // DataPageHeader
  thrift.fieldI32(1, checkedSize(static_cast<std::size_t>(values), column.name));
  thrift.fieldI32(2, kEncodingPlain);
  thrift.fieldI32(3, kEncodingRle);
  thrift.fieldI32(4, kEncodingRle);
  thrift.endStruct();
  thrift.endStruct();
  header.insert(header.end(), page.begin(), page.end());
  return header;
}

void ParquetTable::encodeSchema(ThriftCompactWriter& thrift) const {
  std::size_t elements = 1;
  for (const Column& column : columns_) {
    elements += column.kind == Kind::kFloatList ? 3 : 1;
  }
  thrift.fieldList(2, Thrift::Type::kStruct, elements);
  thrift.beginStruct();  // the root
  thrift.fieldString(4, "schema");
  thrift.fieldI32(5, static_cast<std::int32_t>(columns_.size()));
  thrift.endStruct();
  for (const Column& column : columns_) {
    thrift.beginStruct();
    if (column.kind == Kind::kFloatList) {  // required group (LIST) { repeated group list {
      thrift.fieldI32(3, kRequired);        //   required float element; } }
      thrift.fieldString(4, column.name);
      thrift.fieldI32(5, 1);
      thrift.fieldI32(6, kConvertedList);
      thrift.fieldStruct(10);  // LogicalType
      thrift.fieldStruct(kLogicalList);
      thrift.endStruct();
      thrift.endStruct();
      thrift.endStruct();
      thrift.beginStruct();
      thrift.fieldI32(3, kRepeated);
      thrift.fieldString(4, "list");
      thrift.fieldI32(5, 1);
      thrift.endStruct();
      thrift.beginStruct();
      thrift.fieldI32(1, kTypeFloat);
      thrift.fieldI32(3, kRequired);
      thrift.fieldString(4, "element");
      thrift.endStruct();
      continue;
    }
    thrift.fieldI32(1, physicalType(column.kind));
    thrift.fieldI32(3, kRequired);
    thrift.fieldString(4, column.name);
    if (column.kind == Kind::kString) {
      thrift.fieldI32(6, kConvertedUtf8);
      thrift.fieldStruct(10);
      thrift.fieldStruct(kLogicalString);
      thrift.endStruct();
      thrift.endStruct();
    }
    thrift.endStruct();
  }
}

void ParquetTable::encodeRowGroup(ThriftCompactWriter& thrift,
                                  const std::vector<ChunkPlace>& chunks, std::int64_t rows) const {
  thrift.beginStruct();  // RowGroup
  thrift.fieldList(1, Thrift::Type::kStruct, columns_.size());
  std::int64_t bytes = 0;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const Column& column = columns_[c];
    const ChunkPlace& chunk = chunks[c];
    bytes += chunk.size;
    thrift.beginStruct();  // ColumnChunk
    thrift.fieldI64(2, chunk.offset);
    thrift.fieldStruct(3);  // ColumnMetaData
    thrift.fieldI32(1, physicalType(column.kind));
    thrift.fieldList(2, Thrift::Type::kI32, 2);
    thrift.elementI32(kEncodingPlain);
    thrift.elementI32(kEncodingRle);
    const bool list = column.kind == Kind::kFloatList;
    thrift.fieldList(3, Thrift::Type::kBinary, list ? 3 : 1);
    thrift.elementString(column.name);
    if (list) {
      thrift.elementString("list");
      thrift.elementString("element");
    }
    thrift.fieldI32(4, kCodecUncompressed);
    thrift.fieldI64(5, chunk.values);
    thrift.fieldI64(6, chunk.size);
    thrift.fieldI64(7, chunk.size);
    thrift.fieldI64(9, chunk.offset);
    thrift.endStruct();
    thrift.endStruct();
  }
  thrift.fieldI64(2, bytes);
  thrift.fieldI64(3, rows);
  thrift.endStruct();
}

std::vector<std::uint8_t> ParquetTable::serialize(std::int64_t row_group_rows) const {
  if (row_group_rows < 1) {
    throw std::invalid_argument("parquet: a row group needs at least one row");
  }
  Bytes file = {'P', 'A', 'R', '1'};
  std::vector<std::vector<ChunkPlace>> groups;
  std::vector<std::int64_t> group_rows;
  for (std::int64_t first = 0; first < rows_; first += row_group_rows) {
    const std::int64_t count = std::min(row_group_rows, rows_ - first);
    std::vector<ChunkPlace> chunks;
    for (const Column& column : columns_) {
      std::int64_t values = 0;
      const Bytes page = encodePage(column, first, count, values);
      chunks.push_back(
          {static_cast<std::int64_t>(file.size()), static_cast<std::int64_t>(page.size()), values});
      file.insert(file.end(), page.begin(), page.end());
    }
    groups.push_back(std::move(chunks));
    group_rows.push_back(count);
  }

  Bytes footer;
  Thrift thrift(footer);
  thrift.beginStruct();   // FileMetaData
  thrift.fieldI32(1, 1);  // version
  encodeSchema(thrift);
  thrift.fieldI64(3, rows_);
  thrift.fieldList(4, Thrift::Type::kStruct, groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    encodeRowGroup(thrift, groups[g], group_rows[g]);
  }
  if (!metadata_.empty()) {
    thrift.fieldList(5, Thrift::Type::kStruct, metadata_.size());
    for (const auto& [key, value] : metadata_) {
      thrift.beginStruct();  // KeyValue
      thrift.fieldString(1, key);
      thrift.fieldString(2, value);
      thrift.endStruct();
    }
  }
  thrift.fieldString(6, "comply");
  thrift.endStruct();
  file.insert(file.end(), footer.begin(), footer.end());
  appendLittleEndian(file, static_cast<std::uint32_t>(footer.size()));
  file.insert(file.end(), {'P', 'A', 'R', '1'});
  return file;
}

void ParquetTable::write(const std::filesystem::path& path, std::int64_t row_group_rows) const {
  const Bytes bytes = serialize(row_group_rows);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    throw std::runtime_error("parquet: cannot write " + path.string());
  }
}

std::vector<ParquetTable::NumericColumn> ParquetTable::numericColumns() const {
  std::vector<NumericColumn> out;
  for (const Column& column : columns_) {
    if (column.kind != Kind::kString) {
      out.push_back({column.name, column.width, column.int64s, column.floats, column.doubles});
    }
  }
  return out;
}

}  // namespace comply::exporter
