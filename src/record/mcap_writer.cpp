// The MCAP writer (see mcap_writer.hpp). Records are assembled in memory and appended with
// write(2), whole, so the file on disk only ever ends at a record boundary or inside the last
// record being appended.

#include "comply/record/mcap_writer.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>

#include "comply/core/output_folder.hpp"
#include "mcap_format.hpp"
#include "mcap_records.hpp"

namespace comply::record {

using mcap::closeRecord;
using mcap::openRecord;
using mcap::put;
using mcap::putString;

std::string_view toString(Compression compression) {
  return compression == Compression::kZstd ? "zstd" : "";
}

void checkRecordingFolder(const std::string& path) {
  if (const std::string why = missingFolderOf(path); !why.empty()) {
    throw McapError("cannot record to " + path + ": " + why);
  }
}

McapWriter::McapWriter(const std::string& path, McapWriterOptions options)
    : path_(path), options_(std::move(options)) {
  checkRecordingFolder(path);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw McapError("cannot record to " + path + ": " + std::strerror(errno));
  }
  if (options_.compression == Compression::kZstd) {
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, options_.zstd_level);
    zstd_ = context;
  }
  std::vector<std::uint8_t> bytes(std::begin(mcap::kMagic), std::end(mcap::kMagic));
  mcap::appendHeaderRecord(bytes, options_.profile, options_.library);
  append(bytes);
  chunk_.reserve(options_.chunk_bytes + 4096);
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (const McapError&) {
    // close() is what reports errors; a destructor can only leave the complete part behind.
  }
  if (fd_ >= 0) {
    ::close(fd_);
  }
  ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(zstd_));
}

void McapWriter::fail(const char* what) {
  const int error = errno;
  throw McapError(std::string("recording to ") + path_ + " failed (" + what +
                  "): " + std::strerror(error));
}

void McapWriter::append(const std::vector<std::uint8_t>& bytes) {
  if (fd_ < 0) {
    throw McapError("recording to " + path_ + ": the file is closed");
  }
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      if (n == 0) {
        errno = EIO;
      }
      fail("write");
    }
    done += static_cast<std::size_t>(n);
  }
  file_offset_ += bytes.size();
}

std::uint16_t McapWriter::addSchema(std::string_view name, std::string_view encoding,
                                    std::string_view data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({std::string(name), std::string(encoding), std::string(data)});
  std::vector<std::uint8_t> bytes;
  mcap::appendSchemaRecord(bytes, id, name, encoding, data);
  append(bytes);
  return id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, std::string_view topic,
                                     std::string_view message_encoding, const StringMap& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back({schema_id, std::string(topic), std::string(message_encoding), metadata, 0});
  std::vector<std::uint8_t> bytes;
  mcap::appendChannelRecord(bytes, id, schema_id, topic, message_encoding, metadata);
  append(bytes);
  return id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns,
                       std::uint64_t publish_time_ns, std::span<const std::uint8_t> data) {
  if (channel_id >= channels_.size()) {
    throw McapError("recording to " + path_ + ": no channel " + std::to_string(channel_id));
  }
  if (!chunk_.empty() &&
      (chunk_.size() >= options_.chunk_bytes ||
       log_time_ns >= chunk_start_time_ + static_cast<std::uint64_t>(options_.chunk_span_ns))) {
    writeChunk();
  }
  if (chunk_.empty()) {
    chunk_start_time_ = chunk_end_time_ = log_time_ns;
  }
  chunk_start_time_ = std::min(chunk_start_time_, log_time_ns);
  chunk_end_time_ = std::max(chunk_end_time_, log_time_ns);
  chunk_messages_[channel_id].emplace_back(log_time_ns, chunk_.size());
  mcap::appendMessageRecord(chunk_, channel_id, channels_[channel_id].sequence++, log_time_ns,
                            publish_time_ns, data);

  message_start_time_ =
      message_count_ == 0 ? log_time_ns : std::min(message_start_time_, log_time_ns);
  message_end_time_ = std::max(message_end_time_, log_time_ns);
  ++message_count_;
  ++channel_message_counts_[channel_id];
}

void McapWriter::writeChunk() {
  if (chunk_.empty()) {
    return;
  }
  std::span<const std::uint8_t> records(chunk_);
  if (options_.compression == Compression::kZstd) {
    compressed_.resize(ZSTD_compressBound(chunk_.size()));
    const std::size_t size = ZSTD_compress2(static_cast<ZSTD_CCtx*>(zstd_), compressed_.data(),
                                            compressed_.size(), chunk_.data(), chunk_.size());
    if (ZSTD_isError(size) != 0) {
      throw McapError("recording to " + path_ + ": zstd: " + ZSTD_getErrorName(size));
    }
    records = std::span<const std::uint8_t>(compressed_.data(), size);
  }
  // The chunk and its message indexes go out in one write: a crash leaves either all of it or
  // a torn tail that a reader stops at.
  std::vector<std::uint8_t> bytes;
  bytes.reserve(records.size() + 256);
  mcap::appendChunkRecord(bytes, chunk_start_time_, chunk_end_time_, chunk_,
                          toString(options_.compression), records);

  ChunkIndex index;
  index.start_time = chunk_start_time_;
  index.end_time = chunk_end_time_;
  index.offset = file_offset_;
  index.length = bytes.size();
  index.compressed_size = records.size();
  index.uncompressed_size = chunk_.size();
  for (const auto& [channel, entries] : chunk_messages_) {
    index.message_index_offsets[channel] = file_offset_ + bytes.size();
    mcap::appendMessageIndexRecord(bytes, channel, entries);
  }
  index.message_index_length = file_offset_ + bytes.size() - index.offset - index.length;
  append(bytes);
  chunk_indexes_.push_back(std::move(index));
  chunk_.clear();
  chunk_messages_.clear();
}

void McapWriter::addMetadata(std::string name, StringMap metadata) {
  metadata_.emplace_back(std::move(name), std::move(metadata));
}

void McapWriter::flush() {
  writeChunk();
}

void McapWriter::abandon() noexcept {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

void McapWriter::close() {
  if (fd_ < 0) {
    return;
  }
  writeChunk();
  std::vector<std::uint8_t> bytes;
  // Metadata records, then the data end: the end of the data section.
  std::vector<mcap::MetadataIndex> metadata_indexes;
  for (const auto& [name, map] : metadata_) {
    const std::uint64_t offset = file_offset_ + bytes.size();
    mcap::appendMetadataRecord(bytes, name, map);
    metadata_indexes.push_back({offset, file_offset_ + bytes.size() - offset, name});
  }
  mcap::appendDataEndRecord(bytes);

  // The summary: one group per record kind, each listed in the summary offsets.
  const std::uint64_t summary_start = file_offset_ + bytes.size();
  std::vector<mcap::SummaryGroup> groups;
  const auto group = [&](mcap::Opcode opcode, auto&& write_records) {
    const std::uint64_t start = file_offset_ + bytes.size();
    write_records();
    const std::uint64_t length = file_offset_ + bytes.size() - start;
    if (length > 0) {
      groups.push_back({opcode, start, length});
    }
  };
  group(mcap::kSchema, [&] {
    for (std::size_t i = 0; i < schemas_.size(); ++i) {
      mcap::appendSchemaRecord(bytes, static_cast<std::uint16_t>(i + 1), schemas_[i].name,
                               schemas_[i].encoding, schemas_[i].data);
    }
  });
  group(mcap::kChannel, [&] {
    for (std::size_t i = 0; i < channels_.size(); ++i) {
      const Channel& channel = channels_[i];
      mcap::appendChannelRecord(bytes, static_cast<std::uint16_t>(i), channel.schema_id,
                                channel.topic, channel.message_encoding, channel.metadata);
    }
  });
  group(mcap::kStatistics, [&] { appendStatisticsRecord(bytes); });
  group(mcap::kMetadataIndex, [&] {
    for (const mcap::MetadataIndex& index : metadata_indexes) {
      mcap::appendMetadataIndexRecord(bytes, index);
    }
  });
  group(mcap::kChunkIndex, [&] {
    for (const ChunkIndex& index : chunk_indexes_) {
      appendChunkIndexRecord(bytes, index);
    }
  });
  const std::uint64_t summary_offset_start = file_offset_ + bytes.size();
  for (const mcap::SummaryGroup& summary_group : groups) {
    mcap::appendSummaryOffsetRecord(bytes, summary_group);
  }
  mcap::appendFooterRecord(bytes, summary_start, summary_offset_start,
                           summary_start - file_offset_);
  append(bytes);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    errno = errno == 0 ? EIO : errno;
    fail("close");
  }
}

void McapWriter::appendStatisticsRecord(std::vector<std::uint8_t>& out) const {
  const std::size_t at = openRecord(out, mcap::kStatistics);
  put(out, message_count_);
  put(out, static_cast<std::uint16_t>(schemas_.size()));
  put(out, static_cast<std::uint32_t>(channels_.size()));
  put(out, std::uint32_t{0});  // attachments
  put(out, static_cast<std::uint32_t>(metadata_.size()));
  put(out, static_cast<std::uint32_t>(chunk_indexes_.size()));
  put(out, message_start_time_);
  put(out, message_end_time_);
  mcap::putPairs(out, channel_message_counts_);
  closeRecord(out, at);
}

void McapWriter::appendChunkIndexRecord(std::vector<std::uint8_t>& out,
                                        const ChunkIndex& index) const {
  const std::size_t at = openRecord(out, mcap::kChunkIndex);
  put(out, index.start_time);
  put(out, index.end_time);
  put(out, index.offset);
  put(out, index.length);
  mcap::putPairs(out, index.message_index_offsets);  // channel: u16, offset: u64
  put(out, index.message_index_length);
  putString(out, toString(options_.compression));
  put(out, index.compressed_size);
  put(out, index.uncompressed_size);
  closeRecord(out, at);
}

}  // namespace comply::record
