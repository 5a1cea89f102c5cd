// A video file from PNG frames through ffmpeg (see video_encoder.hpp): ffmpeg reads the PNGs
// from a pipe (its image2pipe demuxer), so no frame touches the disk before it is encoded.

#include "video_encoder.hpp"

#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace comply::exporter {
namespace {

std::string fpsText(double fps) {
  std::ostringstream text;
  text.precision(17);
  text << fps;
  return text.str();
}

std::vector<std::string> encoderArguments(const std::filesystem::path& file, double fps) {
  const std::string rate = fpsText(fps);
  return {"-hide_banner", "-nostats", "-loglevel", "error", "-y",         "-f",     "image2pipe",
          "-framerate",   rate,       "-c:v",      "png",   "-i",         "pipe:0", "-c:v",
          "libx264",      "-pix_fmt", "yuv420p",   "-g",    "2",          "-crf",   "18",
          "-preset",      "veryfast", "-r",        rate,    file.string()};
}

}  // namespace

VideoEncoder::VideoEncoder(std::filesystem::path file, double fps)
    : file_(std::move(file)),
      ffmpeg_(encoderArguments(file_, fps), FfmpegProcess::Pipe::kToStdin,
              file_.string() + ".ffmpeg.log") {}

VideoEncoder::~VideoEncoder() = default;

void VideoEncoder::frame(std::span<const std::uint8_t> png) {
  if (ffmpeg_.fd() < 0 || !writeAll(ffmpeg_.fd(), png.data(), png.size())) {
    const std::string why = ffmpeg_.wait();
    throw std::runtime_error("encoding frame " + std::to_string(frames_) + " of " + file_.string() +
                             ": " + (why.empty() ? "ffmpeg stopped" : why));
  }
  ++frames_;
}

void VideoEncoder::finish() {
  const std::string why = ffmpeg_.wait();
  if (!why.empty()) {
    throw std::runtime_error("writing " + file_.string() + ": " + why);
  }
}

}  // namespace comply::exporter
