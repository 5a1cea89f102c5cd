#pragma once
// Appends CDR as ROS 2 puts it on the wire (XCDR1, little endian): the 4-byte encapsulation
// header, then every primitive aligned to its size counted from the byte after that header;
// strings as a uint32 length with the NUL, sequences as a uint32 count; the message padded to a
// multiple of 4 bytes. Private to the transport.

#include <bit>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace comply::transport::cdr {

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {
    out_.assign(4, 0x00);
    out_[1] = 0x01;  // CDR_LE, no options
  }
  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &value, sizeof(T));  // x86 and ARM are little endian
  }
  void putBool(bool value) { put<std::uint8_t>(value ? 1 : 0); }
  void putString(std::string_view text) {
    put(static_cast<std::uint32_t>(text.size() + 1));
    out_.insert(out_.end(), text.begin(), text.end());
    out_.push_back(0);
  }
  /// A fixed array (no count).
  template <typename T>
  void putArray(const T* values, std::size_t count) {
    if (count == 0) {
      return;
    }
    align(sizeof(T));
    const std::size_t at = out_.size();
    out_.resize(at + count * sizeof(T));
    std::memcpy(out_.data() + at, values, count * sizeof(T));
  }
  /// A sequence: the count, then the elements.
  template <typename T>
  void putSequence(const T* values, std::size_t count) {
    put(static_cast<std::uint32_t>(count));
    putArray(values, count);
  }
  void putCount(std::size_t count) { put(static_cast<std::uint32_t>(count)); }
  /// Ends the message: XCDR pads it to a multiple of 4 and states the padding in the low bits of
  /// the encapsulation options, as CycloneDDS does on the wire.
  void finish() {
    const std::size_t padding = (4 - (out_.size() - 4) % 4) % 4;
    out_.resize(out_.size() + padding, 0);
    out_[3] = static_cast<std::uint8_t>(padding);
  }

 private:
  void align(std::size_t size) {
    const std::size_t offset = out_.size() - 4;
    out_.resize(out_.size() + (size - offset % size) % size, 0);
  }
  std::vector<std::uint8_t>& out_;
};

static_assert(std::endian::native == std::endian::little, "CDR_LE is written as memory holds it");

}  // namespace comply::transport::cdr
