#include "thrift_compact.hpp"

#include <stdexcept>

namespace comply::exporter {

void ThriftCompactWriter::beginStruct() {
  last_field_.push_back(0);
}

void ThriftCompactWriter::endStruct() {
  if (last_field_.empty()) {
    throw std::logic_error("thrift: endStruct without an open struct");
  }
  out_.push_back(0);  // stop field
  last_field_.pop_back();
}

void ThriftCompactWriter::fieldHeader(std::int16_t id, Type type) {
  if (last_field_.empty()) {
    throw std::logic_error("thrift: a field outside any struct");
  }
  const int delta = id - last_field_.back();
  if (delta > 0 && delta <= 15) {
    out_.push_back(static_cast<std::uint8_t>((delta << 4) | static_cast<int>(type)));
  } else {  // the long form: the type, then the id itself as a zigzag varint
    out_.push_back(static_cast<std::uint8_t>(type));
    varint(zigzag(id));
  }
  last_field_.back() = id;
}

void ThriftCompactWriter::varint(std::uint64_t value) {
  while (value >= 0x80) {
    out_.push_back(static_cast<std::uint8_t>(value | 0x80));
    value >>= 7;
  }
  out_.push_back(static_cast<std::uint8_t>(value));
}

void ThriftCompactWriter::fieldI32(std::int16_t id, std::int32_t value) {
  fieldHeader(id, Type::kI32);
  varint(zigzag(value));
}

void ThriftCompactWriter::fieldI64(std::int16_t id, std::int64_t value) {
  fieldHeader(id, Type::kI64);
  varint(zigzag(value));
}

void ThriftCompactWriter::fieldString(std::int16_t id, std::string_view value) {
  fieldHeader(id, Type::kBinary);
  elementString(value);
}

void ThriftCompactWriter::fieldStruct(std::int16_t id) {
  fieldHeader(id, Type::kStruct);
  beginStruct();
}

void ThriftCompactWriter::fieldList(std::int16_t id, Type element, std::size_t size) {
  fieldHeader(id, Type::kList);
  const auto type = static_cast<std::uint8_t>(element);
  if (size < 15) {
    out_.push_back(static_cast<std::uint8_t>((size << 4) | type));
  } else {
    out_.push_back(static_cast<std::uint8_t>(0xF0 | type));
    varint(size);
  }
}

void ThriftCompactWriter::elementI32(std::int32_t value) {
  varint(zigzag(value));
}

void ThriftCompactWriter::elementString(std::string_view value) {
  varint(value.size());
  out_.insert(out_.end(), value.begin(), value.end());
}

}  // namespace comply::exporter
