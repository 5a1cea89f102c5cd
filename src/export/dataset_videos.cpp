// A dataset's videos (see dataset_videos.hpp).

#include "dataset_videos.hpp"

#include <limits>
#include <stdexcept>

#include "recording_images.hpp"

namespace comply::exporter {

void DatasetVideos::open(const std::filesystem::path& recording, const std::string& camera,
                         int width_px, int height_px) {
  if (width_px % 2 != 0 || height_px % 2 != 0) {
    throw std::runtime_error(recording.string() + ": camera '" + camera + "' is " +
                             std::to_string(width_px) + " x " + std::to_string(height_px) +
                             ": a video of 4:2:0 chroma needs an even width and height");
  }
  CameraVideo video;
  video.key = "observation.images." + camera;
  video.width_px = width_px;
  video.height_px = height_px;
  video.file = std::filesystem::path("videos") / video.key / "chunk-000" / "file-000.mp4";
  std::filesystem::create_directories((folder_ / video.file).parent_path());
  video.encoder = std::make_unique<VideoEncoder>(folder_ / video.file, fps_);
  cameras_.push_back(std::move(video));
}

void DatasetVideos::add(const std::filesystem::path& recording,
                        const std::vector<EpisodeFrames>& episodes) {
  const std::vector<CameraFrames> frames = recordingImages(recording);
  const std::string name = recording.string();
  if (first_) {
    for (const CameraFrames& camera : frames) {
      open(recording, camera.camera, camera.width_px, camera.height_px);
    }
    first_ = false;
  }
  if (frames.size() != cameras_.size()) {
    throw std::runtime_error(name + " holds " + std::to_string(frames.size()) +
                             " camera(s), the first recording " + std::to_string(cameras_.size()) +
                             ": a dataset's episodes all have the same cameras");
  }
  for (std::size_t c = 0; c < frames.size(); ++c) {
    const CameraFrames& camera = frames[c];
    CameraVideo& video = cameras_[c];
    if ("observation.images." + camera.camera != video.key || camera.width_px != video.width_px ||
        camera.height_px != video.height_px) {
      throw std::runtime_error(
          name + ": camera '" + camera.camera + "' (" + std::to_string(camera.width_px) + " x " +
          std::to_string(camera.height_px) + ") is not the first " + "recording's " + video.key +
          " (" + std::to_string(video.width_px) + " x " + std::to_string(video.height_px) + ")");
    }
    std::int64_t row = frames_;
    for (std::size_t e = 0; e < episodes.size(); ++e) {
      const EpisodeFrames& episode = episodes[e];
      const std::int64_t end_ns = e + 1 < episodes.size()
                                      ? episodes[e + 1].first_stamp_ns
                                      : std::numeric_limits<std::int64_t>::max();
      video.from_s.push_back(static_cast<double>(row) / fps_);
      for (std::int64_t i = 0; i < episode.frames; ++i) {
        const std::vector<std::uint8_t>* png =
            frameAt(camera, episode.first_stamp_ns, end_ns, static_cast<double>(i) / fps_);
        if (png == nullptr) {
          throw std::runtime_error(name + ": camera '" + camera.camera +
                                   "' has no frame in episode " + std::to_string(e) +
                                   " of the recording");
        }
        video.encoder->frame(*png);
      }
      row += episode.frames;
      video.to_s.push_back(static_cast<double>(row) / fps_);
    }
  }
  for (const EpisodeFrames& episode : episodes) {
    frames_ += episode.frames;
  }
}

void DatasetVideos::finish() {
  for (CameraVideo& video : cameras_) {
    video.encoder->finish();
  }
}

}  // namespace comply::exporter
