#pragma once
// Big-endian bytes in and out, as RTDE puts every number on the wire.

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "comply/ur/rtde_packages.hpp"

namespace comply::ur::wire {

/// The unsigned integer as wide as `Number`.
template <typename Number>
using BitsOf = std::conditional_t<
    sizeof(Number) == 1, std::uint8_t,
    std::conditional_t<sizeof(Number) == 2, std::uint16_t,
                       std::conditional_t<sizeof(Number) == 4, std::uint32_t, std::uint64_t>>>;

/// Writes `value` big-endian at `at` in `out` (which must have room) and returns the byte after
/// it: a package encoded in place, without allocation (the UR backend's answers).
template <typename Number>
std::size_t putAt(std::span<std::uint8_t> out, std::size_t at, Number value) noexcept {
  const auto bits = std::bit_cast<BitsOf<Number>>(value);
  for (int shift = 8 * (static_cast<int>(sizeof(Number)) - 1); shift >= 0; shift -= 8) {
    out[at++] = static_cast<std::uint8_t>(bits >> shift);
  }
  return at;
}

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {}
  template <typename Number>
  void put(Number value) {
    using Bits = BitsOf<Number>;
    const auto bits = std::bit_cast<Bits>(value);
    for (int shift = 8 * (static_cast<int>(sizeof(Number)) - 1); shift >= 0; shift -= 8) {
      out_.push_back(static_cast<std::uint8_t>(bits >> shift));
    }
  }
  void putText(std::string_view text) { out_.insert(out_.end(), text.begin(), text.end()); }

 private:
  std::vector<std::uint8_t>& out_;
};

class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, std::string_view what) : bytes_(bytes), what_(what) {}
  template <typename Number>
  Number get() {
    using Bits = BitsOf<Number>;
    need(sizeof(Number));
    Bits bits = 0;
    for (std::size_t i = 0; i < sizeof(Number); ++i) {
      bits = static_cast<Bits>((static_cast<std::uint64_t>(bits) << 8) | bytes_[at_++]);
    }
    return std::bit_cast<Number>(bits);
  }
  std::string getText(std::size_t size) {
    need(size);
    std::string text(reinterpret_cast<const char*>(bytes_.data() + at_), size);
    at_ += size;
    return text;
  }
  /// What is left, as text (a recipe's names or types end the payload).
  std::string rest() { return getText(bytes_.size() - at_); }
  [[nodiscard]] std::size_t left() const noexcept { return bytes_.size() - at_; }
  void end() const {
    if (at_ != bytes_.size()) {
      throw RtdeError(std::string(what_) + ": " + std::to_string(bytes_.size() - at_) +
                      " bytes past its end");
    }
  }

 private:
  void need(std::size_t size) const {
    if (bytes_.size() - at_ < size) {
      throw RtdeError(std::string(what_) + ": cut short (" + std::to_string(bytes_.size()) +
                      " bytes)");
    }
  }

  std::span<const std::uint8_t> bytes_;
  std::string_view what_;
  std::size_t at_ = 0;
};

}  // namespace comply::ur::wire
