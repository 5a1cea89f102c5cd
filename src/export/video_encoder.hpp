#pragma once
// A video file from PNG frames, encoded by the ffmpeg on PATH (Debian's): H.264 in MP4, 4:2:0,
// a key frame every second frame (LeRobot's default: a decoder seeks to any frame cheaply),
// frame i shown at exactly i / fps. Private to the export module.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace comply::exporter {

class VideoEncoder {
 public:
  /// Starts ffmpeg writing `file` (replaced). Throws std::runtime_error when ffmpeg cannot be
  /// started (not installed: says so).
  VideoEncoder(std::filesystem::path file, double fps);
  /// Stops ffmpeg if finish() was not called (the file is then not to be used).
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
  /// "<what> <file>: ffmpeg exited with status N: <its last words>", after waiting for it.
  [[nodiscard]] std::string failure(const std::string& what);

  std::filesystem::path file_;
  std::filesystem::path log_;  ///< ffmpeg's stderr
  pid_t pid_ = -1;
  int stdin_ = -1;
  std::int64_t frames_ = 0;
};

}  // namespace comply::exporter
