// `comply inspect` (see inspect_command.hpp).

#include "inspect_command.hpp"

#include <filesystem>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

#include "comply/record/mcap_reader.hpp"

namespace comply::app {
namespace {

struct ChannelTally {
  std::uint64_t count = 0;
  std::uint64_t first_ns = 0;
  std::uint64_t last_ns = 0;
};

/// Messages per second over the channel's own span; 0 with fewer than two messages.
double rateHz(const ChannelTally& tally) {
  if (tally.count < 2 || tally.last_ns <= tally.first_ns) {
    return 0.0;
  }
  return static_cast<double>(tally.count - 1) /
         (1e-9 * static_cast<double>(tally.last_ns - tally.first_ns));
}

std::string seconds(std::uint64_t ns) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << 1e-9 * static_cast<double>(ns);
  return text.str();
}

/// Reads the whole file, counting each channel's messages and their log-time span.
record::McapContents readAndTally(const std::string& file,
                                  std::map<std::uint16_t, ChannelTally>& tallies) {
  return record::readMcap(file, [&](const record::McapMessageView& m) {
    ChannelTally& tally = tallies[m.channel_id];
    tally.first_ns = tally.count == 0 ? m.log_time_ns : std::min(tally.first_ns, m.log_time_ns);
    tally.last_ns = std::max(tally.last_ns, m.log_time_ns);
    ++tally.count;
  });
}

/// The log-time span over every channel; `any` is false when no channel holds a message.
struct LogSpan {
  std::uint64_t first = 0;
  std::uint64_t last = 0;
  bool any = false;
};

LogSpan logSpan(const std::map<std::uint16_t, ChannelTally>& tallies) {
  LogSpan span;
  for (const auto& [id, tally] : tallies) {
    if (tally.count > 0) {
      span.first = span.any ? std::min(span.first, tally.first_ns) : tally.first_ns;
      span.last = span.any ? std::max(span.last, tally.last_ns) : tally.last_ns;
      span.any = true;
    }
  }
  return span;
}

/// The file's metadata records: the recorder's own counts in words, any other as key=value.
void printMetadata(const record::McapContents& contents, std::ostream& out) {
  for (const auto& [name, map] : contents.metadata) {
    if (name == "comply_recording") {
      // Recordings from before the choice existed say nothing of it: they dropped.
      const auto when_full = map.find("when_full");
      const bool waited = when_full != map.end() && when_full->second == "wait";
      out << "\ndropped records: " << map.at("records_dropped") << " (written "
          << map.at("records_written") << "; a full lane "
          << (waited ? "waited for the writer" : "dropped") << "); writer thread CPU "
          << map.at("writer_cpu_s") << " s\n";
    } else {
      out << "\n" << name << ":";
      for (const auto& [key, value] : map) {
        out << " " << key << "=" << value;
      }
      out << "\n";
    }
  }
  if (!contents.complete) {
    out << "\n(no dropped-record count: it is written when a recording closes)\n";
  }
}

}  // namespace

int inspectCommand(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  std::map<std::uint16_t, ChannelTally> tallies;
  record::McapContents contents;
  try {
    contents = readAndTally(options.file, tallies);
  } catch (const record::McapError& error) {
    err << "comply inspect: " << error.what() << "\n";
    return 2;
  }
  const auto [first, last, any] = logSpan(tallies);
  const auto file_bytes = std::filesystem::file_size(options.file);

  if (options.json) {
    nlohmann::json document;
    document["file"] = options.file;
    document["bytes"] = file_bytes;
    document["profile"] = contents.profile;
    document["library"] = contents.library;
    document["complete"] = contents.complete;
    document["stopped"] = contents.stopped;
    document["chunks"] = contents.chunks;
    document["messages"] = contents.messages;
    document["chunk_bytes"] = contents.chunk_bytes;
    document["uncompressed_chunk_bytes"] = contents.uncompressed_chunk_bytes;
    document["start_ns"] = first;
    document["end_ns"] = last;
    document["channels"] = nlohmann::json::array();
    for (const record::McapChannelInfo& channel : contents.channels) {
      const ChannelTally tally = tallies[channel.id];
      document["channels"].push_back({{"id", channel.id},
                                      {"topic", channel.topic},
                                      {"type", channel.schema_name},
                                      {"count", tally.count},
                                      {"rate_hz", rateHz(tally)}});
    }
    document["metadata"] = nlohmann::json::object();
    for (const auto& [name, map] : contents.metadata) {
      document["metadata"][name] = map;
    }
    out << document.dump(2) << "\n";
    return contents.complete ? 0 : 1;
  }

  out << options.file << ": " << std::fixed << std::setprecision(1)
      << static_cast<double>(file_bytes) / 1e6 << " MB, " << contents.messages << " messages in "
      << contents.chunks << " chunks, written by " << contents.library << " (profile "
      << contents.profile << ")\n";
  if (contents.uncompressed_chunk_bytes > contents.chunk_bytes) {
    out << "chunks compressed " << std::setprecision(1)
        << static_cast<double>(contents.uncompressed_chunk_bytes) /
               static_cast<double>(std::max<std::uint64_t>(contents.chunk_bytes, 1))
        << "x: " << static_cast<double>(contents.uncompressed_chunk_bytes) / 1e6
        << " MB of messages\n";
  }
  if (any) {
    out << "time span: " << seconds(last - first) << " s (log time " << seconds(first) << " to "
        << seconds(last) << " s)\n";
  }
  if (!contents.complete) {
    out << "INCOMPLETE: " << contents.stopped
        << "; everything up to the last complete chunk is listed\n";
  }
  out << "\n  " << std::left << std::setw(28) << "topic" << std::setw(34) << "type" << std::right
      << std::setw(10) << "messages" << std::setw(12) << "rate [Hz]"
      << "\n";
  for (const record::McapChannelInfo& channel : contents.channels) {
    const ChannelTally tally = tallies[channel.id];
    out << "  " << std::left << std::setw(28) << channel.topic << std::setw(34)
        << channel.schema_name << std::right << std::setw(10) << tally.count << std::setw(12)
        << std::setprecision(1) << rateHz(tally) << "\n";
  }
  printMetadata(contents, out);
  return contents.complete ? 0 : 1;
}

}  // namespace comply::app
