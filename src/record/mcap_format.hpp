#pragma once
// The MCAP record layout (https://mcap.dev/spec) as the writer and the reader share it: opcodes,
// the magic, little-endian field appenders and a bounds-checked cursor. Private to src/record.

#include <cstdint>
#include <cstring>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace comply::record::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

/// CRC-32 (ISO-HDLC, as zlib's crc32) of `bytes`, continuing from `crc`.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0) noexcept;

// --- writing: every field little-endian, strings and byte arrays prefixed by their length ---

template <typename T>
void put(std::vector<std::uint8_t>& out, T value) {
  static_assert(std::is_integral_v<T>);
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i)));
  }
}
inline void putString(std::vector<std::uint8_t>& out, std::string_view text) {
  put(out, static_cast<std::uint32_t>(text.size()));
  out.insert(out.end(), text.begin(), text.end());
}
inline void putStringMap(std::vector<std::uint8_t>& out,
                         const std::map<std::string, std::string>& map) {
  std::vector<std::uint8_t> body;
  for (const auto& [key, value] : map) {
    putString(body, key);
    putString(body, value);
  }
  put(out, static_cast<std::uint32_t>(body.size()));
  out.insert(out.end(), body.begin(), body.end());
}
/// A map or array of fixed-size pairs (MessageIndex records, Statistics' channel counts): its
/// length in bytes, then each pair.
template <typename Pairs>
void putPairs(std::vector<std::uint8_t>& out, const Pairs& pairs) {
  using Pair = typename Pairs::value_type;
  constexpr std::size_t kPairBytes =
      sizeof(typename Pair::first_type) + sizeof(typename Pair::second_type);
  put(out, static_cast<std::uint32_t>(pairs.size() * kPairBytes));
  for (const auto& [first, second] : pairs) {
    put(out, first);
    put(out, second);
  }
}
/// Opens a record: the opcode and a length placeholder; closeRecord() fills the length in.
inline std::size_t openRecord(std::vector<std::uint8_t>& out, Opcode opcode) {
  out.push_back(opcode);
  const std::size_t at = out.size();
  put(out, std::uint64_t{0});
  return at;
}
inline void closeRecord(std::vector<std::uint8_t>& out, std::size_t length_at) {
  const std::uint64_t length = out.size() - length_at - 8;
  for (std::size_t i = 0; i < 8; ++i) {
    out[length_at + i] = static_cast<std::uint8_t>(length >> (8 * i));
  }
}

// --- reading ---

/// Reads fields from a byte range; `ok` turns false (and stays) at the first read past its end.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    T value = 0;
    if (!take(sizeof(T))) {
      return value;
    }
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      value |= static_cast<T>(static_cast<std::uint64_t>(bytes_[at_ - sizeof(T) + i]) << (8 * i));
    }
    return value;
  }
  std::string getString() {
    const auto size = get<std::uint32_t>();
    if (!take(size)) {
      return {};
    }
    return {reinterpret_cast<const char*>(bytes_.data() + at_ - size), size};
  }
  std::map<std::string, std::string> getStringMap() {
    const auto size = get<std::uint32_t>();
    std::map<std::string, std::string> map;
    if (!take(size)) {
      return map;
    }
    Cursor inner(bytes_.subspan(at_ - size, size));
    while (inner.ok() && inner.remaining() > 0) {
      std::string key = inner.getString();
      map[std::move(key)] = inner.getString();
    }
    ok_ = ok_ && inner.ok();
    return map;
  }
  std::span<const std::uint8_t> getBytes(std::size_t size) {
    if (!take(size)) {
      return {};
    }
    return bytes_.subspan(at_ - size, size);
  }
  [[nodiscard]] bool ok() const noexcept { return ok_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - at_; }
  [[nodiscard]] std::size_t offset() const noexcept { return at_; }

 private:
  bool take(std::size_t size) {
    if (!ok_ || size > bytes_.size() - at_) {
      ok_ = false;
      return false;
    }
    at_ += size;
    return true;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

}  // namespace comply::record::mcap
