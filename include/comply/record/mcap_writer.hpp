#pragma once
// A writer of MCAP files (https://mcap.dev/spec), the format the ROS 2 and Foxglove tools read:
// schemas and channels at the top of the data section, messages in chunks (zstd-compressed or
// not), each chunk followed by its message indexes, and on close the summary section (schemas,
// channels, statistics, chunk and metadata indexes, summary offsets) and the footer, so a reader
// can seek.
//
// A file cut short (the process killed, the disk full) stays readable up to its last complete
// chunk: the writer appends whole records only, hands each chunk to the kernel in one write as
// soon as it is closed, and never goes back to patch what it wrote; a streaming reader reads
// records in order until the first incomplete one. A chunk closes at `chunk_bytes` of records or
// after `chunk_span_ns` of log time, whichever comes first, which bounds what a crash can lose.
//
//   McapWriter writer("run.mcap", {});
//   const std::uint16_t schema = writer.addSchema("comply_msgs/msg/ControllerState", "ros2msg",
//   text); const std::uint16_t channel = writer.addChannel(schema, "/comply/state", "cdr", {});
//   writer.write(channel, log_time_ns, log_time_ns, cdr_bytes);
//   writer.close();
//
// Not thread-safe: one thread writes (record::Recorder's writer thread). Every I/O error throws
// McapError naming the file and the system's reason; the file then holds what was complete.

#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace comply::record {

/// An I/O error of a recording (cannot create, disk full, file too large): the message names the
/// file and the reason.
class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Compression : std::uint8_t { kNone, kZstd };
std::string_view toString(Compression compression);  ///< "" or "zstd", as in the file

struct McapWriterOptions {
  Compression compression = Compression::kZstd;
  std::size_t chunk_bytes = 1 << 20;           ///< close a chunk at this many record bytes
  std::int64_t chunk_span_ns = 1'000'000'000;  ///< ... or after this much log time
  std::string profile = "ros2";
  std::string library = "comply";
  int zstd_level = 3;  ///< 1 (fastest) .. 19
};

using StringMap = std::map<std::string, std::string>;

/// Throws McapError when the folder `path` would be created in does not exist ("cannot record
/// to runs/today/a.mcap: the folder 'runs/today' does not exist (create it first: mkdir -p
/// 'runs/today')"). Makes no folder: a mistyped path is an error, not a new tree of folders.
/// Hosts call it before their run starts; McapWriter checks again when it creates the file.
void checkRecordingFolder(const std::string& path);

class McapWriter {
 public:
  /// Creates (or truncates) `path` and writes the magic and the header; throws McapError (its
  /// folder missing: checkRecordingFolder()'s message).
  McapWriter(const std::string& path, McapWriterOptions options);
  /// Closes the file if close() was not called; errors are swallowed there (call close()).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (ids from 1); written at once, outside any chunk.
  std::uint16_t addSchema(std::string_view name, std::string_view encoding, std::string_view data);
  /// A channel of `schema_id` (ids from 0); written at once, outside any chunk.
  std::uint16_t addChannel(std::uint16_t schema_id, std::string_view topic,
                           std::string_view message_encoding, const StringMap& metadata);
  /// One message into the open chunk; the chunk is written when full.
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             std::span<const std::uint8_t> data);
  /// A metadata record (name and string pairs), written with the summary's index on close().
  void addMetadata(std::string name, StringMap metadata);
  /// Writes the open chunk, if any: once written, a record survives the process being killed.
  void flush();
  /// Closes the file as it is, writing nothing more (after an I/O error); close() then does
  /// nothing.
  void abandon() noexcept;
  /// The open chunk, the metadata, the data end, the summary and the footer; then the file is
  /// closed. Idempotent.
  void close();

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::uint64_t messageCount() const noexcept { return message_count_; }
  [[nodiscard]] std::uint64_t bytesWritten() const noexcept { return file_offset_; }
  [[nodiscard]] std::uint64_t chunkCount() const noexcept { return chunk_indexes_.size(); }

 private:
  struct ChunkIndex {
    std::uint64_t start_time = 0, end_time = 0, offset = 0, length = 0;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0, compressed_size = 0, uncompressed_size = 0;
  };
  struct Channel {
    std::uint16_t schema_id = 0;
    std::string topic, message_encoding;
    StringMap metadata;
    std::uint32_t sequence = 0;
  };
  struct Schema {
    std::string name, encoding, data;
  };

  void writeChunk();
  void append(const std::vector<std::uint8_t>& bytes);
  void fail(const char* what);
  // The summary's records of the writer's own state (the other records: mcap_writer.cpp).
  void appendStatisticsRecord(std::vector<std::uint8_t>& out) const;
  void appendChunkIndexRecord(std::vector<std::uint8_t>& out, const ChunkIndex& index) const;

  std::string path_;
  McapWriterOptions options_;
  int fd_ = -1;
  std::uint64_t file_offset_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<std::pair<std::string, StringMap>> metadata_;

  // The open chunk: its records, and per channel the (log time, offset) of each message in it.
  std::vector<std::uint8_t> chunk_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_messages_;
  std::uint64_t chunk_start_time_ = 0, chunk_end_time_ = 0;
  std::vector<std::uint8_t> compressed_;  // reused across chunks
  std::vector<ChunkIndex> chunk_indexes_;

  std::uint64_t message_count_ = 0;
  std::uint64_t message_start_time_ = 0, message_end_time_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;
  void* zstd_ = nullptr;  // ZSTD_CCtx, reused across chunks
};

}  // namespace comply::record
