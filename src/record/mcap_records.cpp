// The MCAP records the writer appends (see mcap_records.hpp).

#include "mcap_records.hpp"

#include <type_traits>

#include "mcap_format.hpp"

namespace comply::record::mcap {
namespace {

/// One field as MCAP spells its type: an integer little-endian, a string (or byte array) after
/// its length, a map after its length in bytes.
template <typename Field>
void putField(std::vector<std::uint8_t>& out, const Field& field) {
  if constexpr (std::is_integral_v<Field>) {
    put(out, field);
  } else if constexpr (std::is_convertible_v<const Field&, std::string_view>) {
    putString(out, field);
  } else {
    putStringMap(out, field);
  }
}

/// A record of `opcode` that holds `fields`, in their order, and nothing else.
template <typename... Fields>
void appendRecord(std::vector<std::uint8_t>& out, Opcode opcode, const Fields&... fields) {
  const std::size_t at = openRecord(out, opcode);
  (putField(out, fields), ...);
  closeRecord(out, at);
}

}  // namespace

void appendHeaderRecord(std::vector<std::uint8_t>& out, std::string_view profile,
                        std::string_view library) {
  appendRecord(out, kHeader, profile, library);
}

void appendSchemaRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::string_view name,
                        std::string_view encoding, std::string_view data) {
  appendRecord(out, kSchema, id, name, encoding, data);  // data: uint32 length + bytes, as a string
}

void appendChannelRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::uint16_t schema_id,
                         std::string_view topic, std::string_view message_encoding,
                         const StringMap& metadata) {
  appendRecord(out, kChannel, id, schema_id, topic, message_encoding, metadata);
}

void appendMessageRecord(std::vector<std::uint8_t>& out, std::uint16_t channel_id,
                         std::uint32_t sequence, std::uint64_t log_time_ns,
                         std::uint64_t publish_time_ns, std::span<const std::uint8_t> data) {
  const std::size_t at = openRecord(out, kMessage);
  put(out, channel_id);
  put(out, sequence);
  put(out, log_time_ns);
  put(out, publish_time_ns);
  out.insert(out.end(), data.begin(), data.end());
  closeRecord(out, at);
}

void appendChunkRecord(std::vector<std::uint8_t>& out, std::uint64_t start_time,
                       std::uint64_t end_time, std::span<const std::uint8_t> plain,
                       std::string_view compression, std::span<const std::uint8_t> records) {
  const std::size_t at = openRecord(out, kChunk);
  put(out, start_time);
  put(out, end_time);
  put(out, static_cast<std::uint64_t>(plain.size()));
  put(out, crc32(plain));
  putString(out, compression);
  put(out, static_cast<std::uint64_t>(records.size()));
  out.insert(out.end(), records.begin(), records.end());
  closeRecord(out, at);
}

void appendMessageIndexRecord(std::vector<std::uint8_t>& out, std::uint16_t channel,
                              const std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries) {
  const std::size_t at = openRecord(out, kMessageIndex);
  put(out, channel);
  putPairs(out, entries);
  closeRecord(out, at);
}

void appendMetadataRecord(std::vector<std::uint8_t>& out, std::string_view name,
                          const StringMap& metadata) {
  appendRecord(out, kMetadata, name, metadata);
}

void appendDataEndRecord(std::vector<std::uint8_t>& out) {
  appendRecord(out, kDataEnd, std::uint32_t{0});  // data section CRC: not computed (0 says so)
}

void appendMetadataIndexRecord(std::vector<std::uint8_t>& out, const MetadataIndex& index) {
  appendRecord(out, kMetadataIndex, index.offset, index.length, index.name);
}

void appendSummaryOffsetRecord(std::vector<std::uint8_t>& out, const SummaryGroup& group) {
  appendRecord(out, kSummaryOffset, group.opcode, group.start, group.length);
}

void appendFooterRecord(std::vector<std::uint8_t>& out, std::uint64_t summary_start,
                        std::uint64_t summary_offset_start, std::size_t summary_begin) {
  // The footer's length is written before the CRC, which covers the summary up to and including
  // the footer's summary_offset_start: opcode and length included.
  out.push_back(kFooter);
  put(out, std::uint64_t{8 + 8 + 4});
  put(out, summary_start);
  put(out, summary_offset_start);
  put(out, crc32(std::span<const std::uint8_t>(out).subspan(summary_begin)));
  out.insert(out.end(), std::begin(kMagic), std::end(kMagic));
}

}  // namespace comply::record::mcap
