#pragma once
// A video file from PNG frames, encoded by the ffmpeg on PATH (Debian's): H.264 in MP4, 4:2:0,
// a key frame every second frame (LeRobot's default: a decoder seeks to any frame cheaply),
// frame i shown at exactly i / fps. Private to the export module.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "ffmpeg_process.hpp"

namespace comply::exporter {

class VideoEncoder {
 public:
  /// Starts ffmpeg writing `file` (replaced). Throws std::runtime_error when ffmpeg cannot be
  /// started (not installed: says so).
  VideoEncoder(std::filesystem::path file, double fps);
  /// Kills ffmpeg if finish() was not called (the file is then not to be used).
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// The next frame, a PNG file's bytes. Throws std::runtime_error with ffmpeg's own message when
  /// it stopped taking frames.
  void frame(std::span<const std::uint8_t> png);
  /// Ends the stream and waits for ffmpeg; throws with its message when it failed.
  void finish();

  [[nodiscard]] std::int64_t frames() const noexcept { return frames_; }
  [[nodiscard]] const std::filesystem::path& file() const noexcept { return file_; }

 private:
  std::filesystem::path file_;
  FfmpegProcess ffmpeg_;
  std::int64_t frames_ = 0;
};

}  // namespace comply::exporter
