#pragma once
// The MCAP records the writer appends (https://mcap.dev/spec), one function each: every one
// appends its whole record (opcode, length, fields) to `out`. Private to src/record.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "comply/record/mcap_writer.hpp"

namespace comply::record::mcap {

/// Where a metadata record is in the file, and its name.
struct MetadataIndex {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  std::string name;
};

/// Where the summary's records of one kind are in the file.
struct SummaryGroup {
  std::uint8_t opcode;
  std::uint64_t start, length;
};

void appendHeaderRecord(std::vector<std::uint8_t>& out, std::string_view profile,
                        std::string_view library);

void appendSchemaRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::string_view name,
                        std::string_view encoding, std::string_view data);

void appendChannelRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::uint16_t schema_id,
                         std::string_view topic, std::string_view message_encoding,
                         const StringMap& metadata);

void appendMessageRecord(std::vector<std::uint8_t>& out, std::uint16_t channel_id,
                         std::uint32_t sequence, std::uint64_t log_time_ns,
                         std::uint64_t publish_time_ns, std::span<const std::uint8_t> data);

/// A chunk of the messages `plain` holds, stored as `records` (`plain` compressed by
/// `compression`, or `plain` itself).
void appendChunkRecord(std::vector<std::uint8_t>& out, std::uint64_t start_time,
                       std::uint64_t end_time, std::span<const std::uint8_t> plain,
                       std::string_view compression, std::span<const std::uint8_t> records);

/// Where in its chunk each message of `channel` is: (log time, offset) pairs.
void appendMessageIndexRecord(std::vector<std::uint8_t>& out, std::uint16_t channel,
                              const std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries);

void appendMetadataRecord(std::vector<std::uint8_t>& out, std::string_view name,
                          const StringMap& metadata);

void appendDataEndRecord(std::vector<std::uint8_t>& out);

void appendMetadataIndexRecord(std::vector<std::uint8_t>& out, const MetadataIndex& index);

void appendSummaryOffsetRecord(std::vector<std::uint8_t>& out, const SummaryGroup& group);

/// The footer and the closing magic; the summary begins at `summary_begin` of `out`, at
/// `summary_start` of the file.
void appendFooterRecord(std::vector<std::uint8_t>& out, std::uint64_t summary_start,
                        std::uint64_t summary_offset_start, std::size_t summary_begin);

}  // namespace comply::record::mcap
