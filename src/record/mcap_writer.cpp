// The MCAP writer (see mcap_writer.hpp). Records are assembled in memory and appended with
// write(2), whole, so the file on disk only ever ends at a record boundary or inside the last
// record being appended.

#include "comply/record/mcap_writer.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>

#include "mcap_format.hpp"

namespace comply::record {

using mcap::closeRecord;
using mcap::openRecord;
using mcap::put;
using mcap::putString;
using mcap::putStringMap;

namespace {

void appendSchemaRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::string_view name,
                        std::string_view encoding, std::string_view data) {
  const std::size_t at = openRecord(out, mcap::kSchema);
  put(out, id);
  putString(out, name);
  putString(out, encoding);
  putString(out, data);  // uint32 length + bytes, as a string is
  closeRecord(out, at);
}

void appendChannelRecord(std::vector<std::uint8_t>& out, std::uint16_t id, std::uint16_t schema_id,
                         std::string_view topic, std::string_view message_encoding,
                         const StringMap& metadata) {
  const std::size_t at = openRecord(out, mcap::kChannel);
  put(out, id);
  put(out, schema_id);
  putString(out, topic);
  putString(out, message_encoding);
  putStringMap(out, metadata);
  closeRecord(out, at);
}

}  // namespace

std::string_view toString(Compression compression) {
  return compression == Compression::kZstd ? "zstd" : "";
}

McapWriter::McapWriter(const std::string& path, McapWriterOptions options)
    : path_(path), options_(std::move(options)) {
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
  const std::size_t at = openRecord(bytes, mcap::kHeader);
  putString(bytes, options_.profile);
  putString(bytes, options_.library);
  closeRecord(bytes, at);
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
  appendSchemaRecord(bytes, id, name, encoding, data);
  append(bytes);
  return id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, std::string_view topic,
                                     std::string_view message_encoding, const StringMap& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back({schema_id, std::string(topic), std::string(message_encoding), metadata, 0});
  std::vector<std::uint8_t> bytes;
  appendChannelRecord(bytes, id, schema_id, topic, message_encoding, metadata);
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
  const std::size_t at = openRecord(chunk_, mcap::kMessage);
  put(chunk_, channel_id);
  put(chunk_, channels_[channel_id].sequence++);
  put(chunk_, log_time_ns);
  put(chunk_, publish_time_ns);
  chunk_.insert(chunk_.end(), data.begin(), data.end());
  closeRecord(chunk_, at);

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
  const std::size_t at = openRecord(bytes, mcap::kChunk);
  put(bytes, chunk_start_time_);
  put(bytes, chunk_end_time_);
  put(bytes, static_cast<std::uint64_t>(chunk_.size()));
  put(bytes, mcap::crc32(chunk_));
  putString(bytes, toString(options_.compression));
  put(bytes, static_cast<std::uint64_t>(records.size()));
  bytes.insert(bytes.end(), records.begin(), records.end());
  closeRecord(bytes, at);

  ChunkIndex index;
  index.start_time = chunk_start_time_;
  index.end_time = chunk_end_time_;
  index.offset = file_offset_;
  index.length = bytes.size();
  index.compressed_size = records.size();
  index.uncompressed_size = chunk_.size();
  for (const auto& [channel, entries] : chunk_messages_) {
    index.message_index_offsets[channel] = file_offset_ + bytes.size();
    const std::size_t index_at = openRecord(bytes, mcap::kMessageIndex);
    put(bytes, channel);
    mcap::putPairs(bytes, entries);
    closeRecord(bytes, index_at);
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
  std::vector<std::tuple<std::uint64_t, std::uint64_t, std::string>> metadata_indexes;
  for (const auto& [name, map] : metadata_) {
    const std::uint64_t offset = file_offset_ + bytes.size();
    const std::size_t at = openRecord(bytes, mcap::kMetadata);
    putString(bytes, name);
    putStringMap(bytes, map);
    closeRecord(bytes, at);
    metadata_indexes.emplace_back(offset, file_offset_ + bytes.size() - offset, name);
  }
  const std::size_t at = openRecord(bytes, mcap::kDataEnd);
  put(bytes, std::uint32_t{0});  // data section CRC: not computed (0 says so)
  closeRecord(bytes, at);

  // The summary: one group per record kind, each listed in the summary offsets.
  const std::uint64_t summary_start = file_offset_ + bytes.size();
  struct Group {
    std::uint8_t opcode;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
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
      appendSchemaRecord(bytes, static_cast<std::uint16_t>(i + 1), schemas_[i].name,
                         schemas_[i].encoding, schemas_[i].data);
    }
  });
  group(mcap::kChannel, [&] {
    for (std::size_t i = 0; i < channels_.size(); ++i) {
      const Channel& channel = channels_[i];
      appendChannelRecord(bytes, static_cast<std::uint16_t>(i), channel.schema_id, channel.topic,
                          channel.message_encoding, channel.metadata);
    }
  });
  group(mcap::kStatistics, [&] {
    const std::size_t record = openRecord(bytes, mcap::kStatistics);
    put(bytes, message_count_);
    put(bytes, static_cast<std::uint16_t>(schemas_.size()));
    put(bytes, static_cast<std::uint32_t>(channels_.size()));
    put(bytes, std::uint32_t{0});  // attachments
    put(bytes, static_cast<std::uint32_t>(metadata_.size()));
    put(bytes, static_cast<std::uint32_t>(chunk_indexes_.size()));
    put(bytes, message_start_time_);
    put(bytes, message_end_time_);
    mcap::putPairs(bytes, channel_message_counts_);
    closeRecord(bytes, record);
  });
  group(mcap::kMetadataIndex, [&] {
    for (const auto& [offset, length, name] : metadata_indexes) {
      const std::size_t record = openRecord(bytes, mcap::kMetadataIndex);
      put(bytes, offset);
      put(bytes, length);
      putString(bytes, name);
      closeRecord(bytes, record);
    }
  });
  group(mcap::kChunkIndex, [&] {
    for (const ChunkIndex& index : chunk_indexes_) {
      const std::size_t record = openRecord(bytes, mcap::kChunkIndex);
      put(bytes, index.start_time);
      put(bytes, index.end_time);
      put(bytes, index.offset);
      put(bytes, index.length);
      put(bytes, static_cast<std::uint32_t>(index.message_index_offsets.size() * 10));
      for (const auto& [channel, offset] : index.message_index_offsets) {
        put(bytes, channel);
        put(bytes, offset);
      }
      put(bytes, index.message_index_length);
      putString(bytes, toString(options_.compression));
      put(bytes, index.compressed_size);
      put(bytes, index.uncompressed_size);
      closeRecord(bytes, record);
    }
  });
  const std::uint64_t summary_offset_start = file_offset_ + bytes.size();
  for (const Group& g : groups) {
    const std::size_t record = openRecord(bytes, mcap::kSummaryOffset);
    put(bytes, g.opcode);
    put(bytes, g.start);
    put(bytes, g.length);
    closeRecord(bytes, record);
  }
  // The footer's length is written before the CRC, which covers the summary up to and including
  // the footer's summary_offset_start: opcode and length included.
  bytes.push_back(mcap::kFooter);
  put(bytes, std::uint64_t{8 + 8 + 4});
  put(bytes, summary_start);
  put(bytes, summary_offset_start);
  const std::size_t summary_begin = summary_start - file_offset_;
  put(bytes, mcap::crc32(std::span<const std::uint8_t>(bytes).subspan(summary_begin)));
  bytes.insert(bytes.end(), std::begin(mcap::kMagic), std::end(mcap::kMagic));
  append(bytes);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    errno = errno == 0 ? EIO : errno;
    fail("close");
  }
}

}  // namespace comply::record
