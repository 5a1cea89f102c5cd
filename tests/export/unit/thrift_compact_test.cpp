// Thrift's compact protocol as Parquet's footer uses it, byte for byte against the protocol's
// specification: field headers (short and long form), zigzag varints, strings, lists (short and
// long size), nested structs and their stop bytes.

#include "thrift_compact.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace comply::exporter {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(ThriftCompact, FieldsAreDeltasWithTheirTypeAndIntegersZigzagVarints) {
  Bytes out;
  ThriftCompactWriter thrift(out);
  thrift.beginStruct();
  thrift.fieldI32(1, 1);        // delta 1, i32 (5); zigzag(1) = 2
  thrift.fieldI64(3, -1);       // delta 2, i64 (6); zigzag(-1) = 1
  thrift.fieldI64(4, 300);      // zigzag(300) = 600 = 0xD8 0x04
  thrift.fieldString(6, "ab");  // delta 2, binary (8); length 2
  thrift.fieldI32(30, -64);     // delta 24: long form, type then zigzag(30) = 60; zigzag(-64) = 127
  thrift.endStruct();
  const Bytes expected = {0x15, 0x02, 0x26, 0x01, 0x16, 0xD8, 0x04, 0x28,
                          0x02, 'a',  'b',  0x05, 0x3C, 0x7F, 0x00};
  EXPECT_EQ(out, expected);
}

TEST(ThriftCompact, ListsCarryTheirSizeShortOrLongAndStructsNestWithTheirOwnFieldIds) {
  Bytes out;
  ThriftCompactWriter thrift(out);
  thrift.beginStruct();
  thrift.fieldList(2, ThriftCompactWriter::Type::kI32, 2);  // 0x29, then (2 << 4) | 5
  thrift.elementI32(0);
  thrift.elementI32(3);
  thrift.fieldList(3, ThriftCompactWriter::Type::kBinary, 15);  // long size: 0xF8, varint 15
  for (int i = 0; i < 15; ++i) {
    thrift.elementString("");
  }
  thrift.fieldStruct(5);  // delta 2, struct (12)
  thrift.fieldI32(1, 0);  // the nested struct's ids start again at 0
  thrift.endStruct();
  thrift.fieldI32(6, 0);  // and the outer one's go on from 5
  thrift.endStruct();
  Bytes expected = {0x29, 0x25, 0x00, 0x06, 0x19, 0xF8, 0x0F};
  expected.insert(expected.end(), 15, 0x00);
  expected.insert(expected.end(), {0x2C, 0x15, 0x00, 0x00, 0x15, 0x00, 0x00});
  EXPECT_EQ(out, expected);
}

TEST(ThriftCompact, AFieldOutsideAStructOrAnUnmatchedEndIsAProgrammingError) {
  Bytes out;
  ThriftCompactWriter thrift(out);
  EXPECT_THROW(thrift.fieldI32(1, 0), std::logic_error);
  EXPECT_THROW(thrift.endStruct(), std::logic_error);
}

}  // namespace
}  // namespace comply::exporter
