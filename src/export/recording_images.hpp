#pragma once
// A recording's camera frames (the hosts' /<name>/camera/<camera> channels of
// sensor_msgs/msg/CompressedImage, PNG), and the frame in force at a dataset frame's time.
// Private to the export module.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace comply::exporter {

struct CameraFrames {
  std::string camera;                  ///< the channel's last name: /comply/camera/<camera>
  std::vector<std::int64_t> stamp_ns;  ///< each frame's header stamp, ascending
  std::vector<std::vector<std::uint8_t>> png;
  int width_px = 0;
  int height_px = 0;
};

/// Every camera channel of `recording`, by camera name. Throws std::runtime_error naming the
/// file and camera for a frame that is not a PNG, does not decode, is stamped before the one
/// before it or changes size.
std::vector<CameraFrames> recordingImages(const std::filesystem::path& recording);

/// The frame in force `offset_s` after `start_ns` among the frames stamped in [start_ns, end_ns):
/// the last stamped at or before that time; the first one when none is yet (a camera that
/// started after the arm). Null when there is none in the range.
const std::vector<std::uint8_t>* frameAt(const CameraFrames& frames, std::int64_t start_ns,
                                         std::int64_t end_ns, double offset_s);

/// A PNG's width and height from its header; false when `bytes` do not start as a PNG.
bool pngSize(const std::vector<std::uint8_t>& bytes, int& width_px, int& height_px);

}  // namespace comply::exporter
