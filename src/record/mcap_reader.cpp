// The streaming MCAP reader (see mcap_reader.hpp).

#include "comply/record/mcap_reader.hpp"

#include <zstd.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "mcap_format.hpp"

namespace comply::record {
namespace {

using mcap::Cursor;

std::vector<std::uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw McapError("cannot read " + path + ": " + std::strerror(errno));
  }
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Reader {
 public:
  Reader(std::string path, const std::function<void(const McapMessageView&)>& on_message)
      : path_(std::move(path)), on_message_(on_message) {}

  /// The records of `bytes` (the file after its magic, or a chunk's records). Returns false at the
  /// first incomplete record, with `stopped` saying where.
  bool readRecords(std::span<const std::uint8_t> bytes, std::uint64_t base, bool in_chunk) {
    Cursor cursor(bytes);
    while (cursor.remaining() > 0) {
      const std::uint64_t at = base + cursor.offset();
      const auto opcode = cursor.get<std::uint8_t>();
      const auto length = cursor.get<std::uint64_t>();
      const std::span<const std::uint8_t> body = cursor.getBytes(length);
      if (!cursor.ok()) {
        contents_.stopped = "incomplete record (opcode " + std::to_string(opcode) + ") at byte " +
                            std::to_string(at);
        return false;
      }
      if (!in_chunk && opcode == mcap::kFooter) {
        footer_ = true;
        footer_start_ = at;
        footer_end_ = base + cursor.offset();
        Cursor footer(body);
        summary_start_ = footer.get<std::uint64_t>();
        footer.get<std::uint64_t>();  // summary offset start
        summary_crc_ = footer.get<std::uint32_t>();
        return true;
      }
      if (!record(opcode, body, at)) {
        return false;
      }
    }
    return true;
  }

  McapContents& contents() { return contents_; }
  [[nodiscard]] bool footer() const { return footer_; }
  [[nodiscard]] std::uint64_t footerEnd() const { return footer_end_; }
  /// The summary's CRC holds (or the file states none).
  [[nodiscard]] bool summaryCrcHolds(std::span<const std::uint8_t> file) const {
    // The CRC covers the summary through the footer's summary_offset_start field.
    const std::uint64_t end = footer_start_ + 1 + 8 + 8 + 8;
    if (summary_crc_ == 0 || summary_start_ == 0 || summary_start_ > end || end > file.size()) {
      return true;
    }
    return mcap::crc32(file.subspan(summary_start_, end - summary_start_)) == summary_crc_;
  }

 private:
  bool record(std::uint8_t opcode, std::span<const std::uint8_t> body, std::uint64_t at) {
    Cursor c(body);
    switch (opcode) {
      case mcap::kHeader:
        readHeader(c);
        break;
      case mcap::kSchema:
        readSchema(c);
        break;
      case mcap::kChannel:
        readChannel(c);
        break;
      case mcap::kMessage:
        readMessage(c);
        break;
      case mcap::kChunk:
        return readChunk(c, at);
      case mcap::kMetadata:
        readMetadata(c);
        break;
      case mcap::kStatistics:
        readStatistics(c);
        break;
      default:  // indexes, summary offsets, data end: what a seeking reader needs, not this one
        break;
    }
    if (!c.ok()) {
      throw McapError(path_ + ": malformed record (opcode " + std::to_string(opcode) +
                      ") at byte " + std::to_string(at));
    }
    return true;
  }

  void readHeader(Cursor& c) {
    contents_.profile = c.getString();
    contents_.library = c.getString();
  }

  void readSchema(Cursor& c) {
    const auto id = c.get<std::uint16_t>();
    Schema schema{c.getString(), c.getString(), c.getString()};
    schemas_[id] = std::move(schema);
  }

  void readChannel(Cursor& c) {
    McapChannelInfo channel;
    channel.id = c.get<std::uint16_t>();
    channel.schema_id = c.get<std::uint16_t>();
    channel.topic = c.getString();
    channel.message_encoding = c.getString();
    channel.metadata = c.getStringMap();
    if (const auto found = schemas_.find(channel.schema_id); found != schemas_.end()) {
      channel.schema_name = found->second.name;
      channel.schema_encoding = found->second.encoding;
      channel.schema_data = found->second.data;
    }
    // The summary repeats the channels: keep the first of each id.
    bool known = false;
    for (const McapChannelInfo& existing : contents_.channels) {
      known = known || existing.id == channel.id;
    }
    if (!known && c.ok()) {
      contents_.channels.push_back(std::move(channel));
    }
  }

  void readMessage(Cursor& c) {
    if (on_message_) {
      McapMessageView message;
      message.channel_id = c.get<std::uint16_t>();
      message.sequence = c.get<std::uint32_t>();
      message.log_time_ns = c.get<std::uint64_t>();
      message.publish_time_ns = c.get<std::uint64_t>();
      message.data = c.getBytes(c.remaining());
      if (c.ok()) {
        on_message_(message);
      }
    }
    ++contents_.messages;
  }

  void readMetadata(Cursor& c) {
    std::string name = c.getString();
    contents_.metadata.emplace_back(std::move(name), c.getStringMap());
  }

  void readStatistics(Cursor& c) {
    McapStatistics s;
    s.message_count = c.get<std::uint64_t>();
    c.get<std::uint16_t>();  // schemas
    c.get<std::uint32_t>();  // channels
    c.get<std::uint32_t>();  // attachments
    c.get<std::uint32_t>();  // metadata
    s.chunk_count = c.get<std::uint32_t>();
    s.message_start_time_ns = c.get<std::uint64_t>();
    s.message_end_time_ns = c.get<std::uint64_t>();
    const auto size = c.get<std::uint32_t>();
    for (std::uint32_t i = 0; i + 10 <= size && c.ok(); i += 10) {
      const auto channel = c.get<std::uint16_t>();
      s.channel_message_counts[channel] = c.get<std::uint64_t>();
    }
    if (c.ok()) {
      contents_.statistics = std::move(s);
    }
  }

  bool readChunk(Cursor& c, std::uint64_t at) {
    c.get<std::uint64_t>();  // start time
    c.get<std::uint64_t>();  // end time
    const auto uncompressed_size = c.get<std::uint64_t>();
    const auto crc = c.get<std::uint32_t>();
    const std::string compression = c.getString();
    const auto size = c.get<std::uint64_t>();
    const std::span<const std::uint8_t> records = c.getBytes(size);
    if (!c.ok()) {
      throw McapError(path_ + ": malformed chunk at byte " + std::to_string(at));
    }
    std::span<const std::uint8_t> plain = records;
    if (compression == "zstd") {
      buffer_.resize(uncompressed_size);
      const std::size_t got =
          ZSTD_decompress(buffer_.data(), buffer_.size(), records.data(), records.size());
      if (ZSTD_isError(got) != 0 || got != uncompressed_size) {
        throw McapError(path_ + ": chunk at byte " + std::to_string(at) + " does not decompress: " +
                        (ZSTD_isError(got) != 0 ? ZSTD_getErrorName(got) : "wrong size"));
      }
      plain = buffer_;
    } else if (!compression.empty()) {
      throw McapError(path_ + ": chunk at byte " + std::to_string(at) + " uses compression '" +
                      compression + "', which comply does not read");
    }
    if (crc != 0 && mcap::crc32(plain) != crc) {
      throw McapError(path_ + ": chunk at byte " + std::to_string(at) + " fails its CRC");
    }
    // The chunk's records are whole: an incomplete one inside is corruption, not truncation.
    std::vector<std::uint8_t> own(plain.begin(), plain.end());
    if (!readRecords(own, 0, true)) {
      throw McapError(path_ + ": chunk at byte " + std::to_string(at) + " holds an " +
                      contents_.stopped);
    }
    ++contents_.chunks;
    contents_.chunk_bytes += records.size();
    contents_.uncompressed_chunk_bytes += plain.size();
    return true;
  }

  struct Schema {
    std::string name, encoding, data;
  };
  std::string path_;
  const std::function<void(const McapMessageView&)>& on_message_;
  McapContents contents_;
  std::map<std::uint16_t, Schema> schemas_;
  std::vector<std::uint8_t> buffer_;
  bool footer_ = false;
  std::uint64_t footer_start_ = 0;
  std::uint64_t footer_end_ = 0;
  std::uint64_t summary_start_ = 0;
  std::uint32_t summary_crc_ = 0;
};

}  // namespace

McapContents readMcap(const std::string& path,
                      const std::function<void(const McapMessageView&)>& on_message) {
  const std::vector<std::uint8_t> file = readFile(path);
  if (file.size() < sizeof(mcap::kMagic) ||
      std::memcmp(file.data(), mcap::kMagic, sizeof(mcap::kMagic)) != 0) {
    throw McapError(path + " is not an MCAP file (no MCAP magic at its start)");
  }
  Reader reader(path, on_message);
  const std::span<const std::uint8_t> records =
      std::span<const std::uint8_t>(file).subspan(sizeof(mcap::kMagic));
  reader.readRecords(records, sizeof(mcap::kMagic), false);
  McapContents& contents = reader.contents();
  if (reader.footer()) {
    if (!reader.summaryCrcHolds(file)) {
      throw McapError(path + ": the summary fails its CRC");
    }
    const std::uint64_t end = reader.footerEnd();
    contents.complete = end + sizeof(mcap::kMagic) == file.size() &&
                        std::memcmp(file.data() + end, mcap::kMagic, sizeof(mcap::kMagic)) == 0;
    if (!contents.complete) {
      contents.stopped = "no closing magic after the footer";
    }
  } else if (contents.stopped.empty()) {
    contents.stopped = "no footer: the file ends after its last complete record";
  }
  return std::move(contents);
}

}  // namespace comply::record
