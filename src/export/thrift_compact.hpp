#pragma once
// Thrift's compact protocol, the encoding of Parquet's page headers and file footer: the subset
// they use (structs, i32, i64, strings, lists of i32, strings and structs). Private to export.
//
// Each field is written as the difference of its id from the previous field's in the same
// struct, with its type in the low nibble; integers are zigzag varints; a struct ends with a 0
// byte. The writer keeps the last field id of every open struct on a stack.

#include <cstdint>
#include <string_view>
#include <vector>

namespace comply::exporter {

class ThriftCompactWriter {
 public:
  /// Compact protocol type ids (those Parquet's structures use).
  enum class Type : std::uint8_t {
    kI32 = 5,
    kI64 = 6,
    kBinary = 8,
    kList = 9,
    kStruct = 12,
  };

  explicit ThriftCompactWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  /// The outermost struct, or one element of a list of structs.
  void beginStruct();
  void endStruct();

  void fieldI32(std::int16_t id, std::int32_t value);
  void fieldI64(std::int16_t id, std::int64_t value);
  void fieldString(std::int16_t id, std::string_view value);
  /// A struct-valued field; close it with endStruct().
  void fieldStruct(std::int16_t id);
  /// A list-valued field of `size` elements of `element`; then write that many elements (i32 and
  /// strings with the element functions, structs with beginStruct()/endStruct()).
  void fieldList(std::int16_t id, Type element, std::size_t size);

  void elementI32(std::int32_t value);
  void elementString(std::string_view value);

 private:
  void fieldHeader(std::int16_t id, Type type);
  void varint(std::uint64_t value);
  static std::uint64_t zigzag(std::int64_t value) {
    return (static_cast<std::uint64_t>(value) << 1) ^ static_cast<std::uint64_t>(value >> 63);
  }

  std::vector<std::uint8_t>& out_;
  std::vector<std::int16_t> last_field_;  // per open struct
};

}  // namespace comply::exporter
