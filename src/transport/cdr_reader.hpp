#pragma once
// Reads what cdr::Writer writes (XCDR1, little endian, after the 4-byte encapsulation header),
// every read bounds-checked: past the end, or a count larger than the bytes left could hold,
// and the reader fails for good, giving zeros from then on. The caller asks ok() once at the
// end. Private to the transport.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>

namespace comply::transport::cdr {

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {
    // CDR_LE (0x0001), the only encoding comply writes.
    ok_ = bytes.size() >= 4 && bytes[0] == 0x00 && bytes[1] == 0x01;
  }
  [[nodiscard]] bool ok() const noexcept { return ok_; }

  template <typename T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    T value{};
    getArray(&value, 1);
    return value;
  }
  bool getBool() { return get<std::uint8_t>() != 0; }
  /// A string: its length with the NUL, the characters, the NUL.
  std::string getString() {
    const auto length = get<std::uint32_t>();
    if (!ok_ || length == 0 || length > left()) {
      ok_ = false;
      return {};
    }
    const auto* text = reinterpret_cast<const char*>(bytes_.data() + at_);
    at_ += length;
    if (text[length - 1] != '\0') {
      ok_ = false;
      return {};
    }
    return {text, length - 1};
  }
  /// A fixed array (no count).
  template <typename T>
  void getArray(T* values, std::size_t count) {
    if (!ok_ || count == 0) {
      return;
    }
    align(sizeof(T));
    if (!ok_ || count > left() / sizeof(T)) {
      ok_ = false;
      std::memset(values, 0, count * sizeof(T));
      return;
    }
    std::memcpy(values, bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
  }
  /// A sequence's count, refused when more than `max` or when the bytes left could not hold that
  /// many elements of at least `element_bytes` each.
  std::size_t getCount(std::size_t element_bytes, std::size_t max = SIZE_MAX) {
    const auto count = get<std::uint32_t>();
    if (!ok_ || count > max || (element_bytes > 0 && count > left() / element_bytes)) {
      ok_ = false;
      return 0;
    }
    return count;
  }

 private:
  [[nodiscard]] std::size_t left() const noexcept { return bytes_.size() - at_; }
  void align(std::size_t size) {
    const std::size_t offset = at_ - 4;
    const std::size_t padding = (size - offset % size) % size;
    if (padding > left()) {
      ok_ = false;
      return;
    }
    at_ += padding;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 4;
  bool ok_ = false;
};

static_assert(std::endian::native == std::endian::little, "CDR_LE is read as memory holds it");

}  // namespace comply::transport::cdr
