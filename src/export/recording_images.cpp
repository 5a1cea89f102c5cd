// A recording's camera frames (see recording_images.hpp).

#include "recording_images.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>

#include "comply/record/mcap_reader.hpp"
#include "comply/transport/compressed_image.hpp"

namespace comply::exporter {
namespace {

std::uint32_t bigEndian32(const std::uint8_t* bytes) {
  return (std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) |
         (std::uint32_t{bytes[2]} << 8) | std::uint32_t{bytes[3]};
}

}  // namespace

bool pngSize(const std::vector<std::uint8_t>& bytes, int& width_px, int& height_px) {
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 24 || std::memcmp(bytes.data(), kSignature, 8) != 0 ||
      std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
    return false;
  }
  const std::uint32_t width = bigEndian32(bytes.data() + 16);
  const std::uint32_t height = bigEndian32(bytes.data() + 20);
  if (width == 0 || height == 0 || width > (1U << 16) || height > (1U << 16)) {
    return false;
  }
  width_px = static_cast<int>(width);
  height_px = static_cast<int>(height);
  return true;
}

std::vector<CameraFrames> recordingImages(const std::filesystem::path& recording) {
  const std::string name = recording.string();
  std::map<std::uint16_t, CameraFrames> cameras;
  for (const record::McapChannelInfo& channel : record::readMcap(name).channels) {
    const std::size_t slash = channel.topic.rfind("/camera/");
    if (channel.schema_name == transport::kCompressedImageType && slash != std::string::npos) {
      cameras[channel.id].camera = channel.topic.substr(slash + 8);
    }
  }
  if (cameras.empty()) {
    return {};
  }
  std::string error;
  (void)record::readMcap(name, [&](const record::McapMessageView& message) {
    const auto found = cameras.find(message.channel_id);
    if (found == cameras.end() || !error.empty()) {
      return;
    }
    CameraFrames& frames = found->second;
    const std::string which =
        name + ": camera '" + frames.camera + "' frame " + std::to_string(frames.png.size());
    transport::CompressedImageMessage image;
    int width = 0;
    int height = 0;
    if (!transport::decodeCdr(message.data, image)) {
      error = which + " does not decode";
    } else if (image.format.find("png") == std::string::npos ||
               !pngSize(image.data, width, height)) {
      error = which + " is not a PNG (format '" + image.format + "'): only PNG frames are exported";
    } else if (!frames.png.empty() && (width != frames.width_px || height != frames.height_px)) {
      error = which + " is " + std::to_string(width) + " x " + std::to_string(height) +
              ", the camera's first " + std::to_string(frames.width_px) + " x " +
              std::to_string(frames.height_px);
    } else if (!frames.stamp_ns.empty() &&
               image.header.stamp.nanoseconds() < frames.stamp_ns.back()) {
      error = which + " is stamped before the one before it";
    } else {
      frames.width_px = width;
      frames.height_px = height;
      frames.stamp_ns.push_back(image.header.stamp.nanoseconds());
      frames.png.push_back(std::move(image.data));
    }
  });
  if (!error.empty()) {
    throw std::runtime_error(error);
  }
  std::vector<CameraFrames> out;
  out.reserve(cameras.size());
  for (auto& [id, frames] : cameras) {
    out.push_back(std::move(frames));
  }
  std::sort(out.begin(), out.end(),
            [](const CameraFrames& a, const CameraFrames& b) { return a.camera < b.camera; });
  return out;
}

const std::vector<std::uint8_t>* frameAt(const CameraFrames& frames, std::int64_t start_ns,
                                         std::int64_t end_ns, double offset_s) {
  const auto begin = std::lower_bound(frames.stamp_ns.begin(), frames.stamp_ns.end(), start_ns);
  const auto end = std::lower_bound(begin, frames.stamp_ns.end(), end_ns);
  if (begin == end) {
    return nullptr;
  }
  // The stamps are whole nanoseconds, i / fps is not: a frame within 1 ns of the time is in it.
  // Offsets from the start, not absolute times: a wall-clock stamp as a double keeps only about
  // a quarter of a microsecond.
  const double limit_ns = offset_s * 1e9 + 1.0;
  const auto after =
      std::upper_bound(begin, end, limit_ns, [start_ns](double limit, std::int64_t stamp) {
        return limit < static_cast<double>(stamp - start_ns);
      });
  const auto at = after == begin ? begin : after - 1;
  return &frames.png[static_cast<std::size_t>(at - frames.stamp_ns.begin())];
}

}  // namespace comply::exporter
