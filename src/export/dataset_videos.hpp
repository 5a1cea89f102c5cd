#pragma once
// A dataset's videos: each camera a recording holds (recording_images.hpp) as one video of every
// episode's frames, one after another, a frame per row of the data table, and where each
// episode's frames are in it. Private to the export module.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "comply/export/recording_frames.hpp"
#include "video_encoder.hpp"

namespace comply::exporter {

struct CameraVideo {
  std::string key;  ///< the dataset's feature: observation.images.<camera>
  int width_px = 0;
  int height_px = 0;
  std::filesystem::path file;  ///< relative to the dataset's folder
  std::vector<double> from_s;  ///< per episode: its first frame's time in the video
  std::vector<double> to_s;    ///< per episode: the end of its last frame
  std::unique_ptr<VideoEncoder> encoder;
};

class DatasetVideos {
 public:
  DatasetVideos(std::filesystem::path folder, double fps) : folder_(std::move(folder)), fps_(fps) {}

  /// The camera frames of `recording` for its `episodes` (recordingEpisodes()), a frame per row.
  /// The first recording names the cameras; every later one must hold the same, at the same
  /// sizes. Throws std::runtime_error naming the recording and camera at fault.
  void add(const std::filesystem::path& recording, const std::vector<EpisodeFrames>& episodes);
  /// Ends every video; throws when ffmpeg failed.
  void finish();

  [[nodiscard]] std::vector<CameraVideo>& cameras() noexcept { return cameras_; }

 private:
  void open(const std::filesystem::path& recording, const std::string& camera, int width_px,
            int height_px);

  std::filesystem::path folder_;
  double fps_;
  bool first_ = true;
  std::vector<CameraVideo> cameras_;
  std::int64_t frames_ = 0;  ///< the rows so far: where the next episode starts in each video
};

}  // namespace comply::exporter
