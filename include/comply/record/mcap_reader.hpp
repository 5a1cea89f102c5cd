#pragma once
// Reads an MCAP file from its start, record by record, as a streaming reader does: what
// `comply inspect`, the recorder's tests and the crash check use. It needs no summary, so a file
// cut short reads up to its last complete record; the summary's statistics are returned when the
// file has them.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "comply/record/mcap_writer.hpp"

namespace comply::record {

struct McapChannelInfo {
  std::uint16_t id = 0;
  std::string topic;
  std::string message_encoding;
  StringMap metadata;
  std::uint16_t schema_id = 0;
  std::string schema_name;  ///< "" when the channel has no schema (id 0)
  std::string schema_encoding;
  std::string schema_data;
};

struct McapMessageView {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0;
  std::uint64_t publish_time_ns = 0;
  std::span<const std::uint8_t> data;  ///< valid during the callback only
};

/// The summary's Statistics record.
struct McapStatistics {
  std::uint64_t message_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

struct McapContents {
  std::string profile;
  std::string library;
  std::vector<McapChannelInfo> channels;  ///< by id order of appearance
  std::vector<std::pair<std::string, StringMap>> metadata;
  std::optional<McapStatistics> statistics;    ///< from the summary, when the file has one
  std::size_t chunks = 0;                      ///< complete chunks read
  std::uint64_t messages = 0;                  ///< messages read (in complete chunks)
  std::uint64_t chunk_bytes = 0;               ///< the complete chunks as stored
  std::uint64_t uncompressed_chunk_bytes = 0;  ///< ... and decompressed
  /// The footer and the closing magic were found: the file was closed properly.
  bool complete = false;
  /// Where and why reading stopped early ("" when complete), e.g. "incomplete chunk at byte N".
  std::string stopped;
};

/// Reads `path`; calls `on_message` for every message of every complete chunk, in file order.
/// Throws McapError when the file cannot be read, is not MCAP, or a chunk fails its CRC or
/// cannot be decompressed.
McapContents readMcap(const std::string& path,
                      const std::function<void(const McapMessageView&)>& on_message = {});

}  // namespace comply::record
