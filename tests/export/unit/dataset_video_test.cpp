// A dataset's camera frames: the frame in force at a row's time within its episode, a PNG's size
// from its header, and the video ffmpeg makes of them (ffprobe counts its frames, ffmpeg decodes
// them back next to the PNGs they came from); the features' statistics.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "comply/sim/image.hpp"
#include "feature_stats.hpp"
#include "recording_images.hpp"
#include "scratch.hpp"
#include "video_encoder.hpp"

namespace comply::exporter {
namespace {

/// Frames stamped at `stamps_ns`, frame k's bytes {k}.
CameraFrames framesAt(const std::vector<std::int64_t>& stamps_ns) {
  CameraFrames frames;
  frames.camera = "front";
  frames.stamp_ns = stamps_ns;
  for (std::size_t k = 0; k < stamps_ns.size(); ++k) {
    frames.png.push_back({static_cast<std::uint8_t>(k)});
  }
  return frames;
}

int which(const std::vector<std::uint8_t>* frame) {
  return frame == nullptr ? -1 : frame->front();
}

TEST(FrameAt, TheLastFrameAtOrBeforeTheRowsTimeWithinItsEpisode) {
  // Two episodes: frames at 0, 50, 100 ms from 1e18 ns (a wall clock: offsets, not absolute
  // doubles, keep a nanosecond), then the next episode's at 150 and 200 ms.
  const std::int64_t start = 1'000'000'000'000'000'000;
  const CameraFrames frames = framesAt(
      {start, start + 50'000'000, start + 100'000'000, start + 150'000'000, start + 200'000'000});
  const std::int64_t next = start + 150'000'000;
  EXPECT_EQ(which(frameAt(frames, start, next, 0.0)), 0);
  EXPECT_EQ(which(frameAt(frames, start, next, 0.0499999)), 0);
  EXPECT_EQ(which(frameAt(frames, start, next, 0.049999999)), 1);  // within the 1 ns tolerance
  EXPECT_EQ(which(frameAt(frames, start, next, 0.05)), 1);              // on the frame's own stamp
  EXPECT_EQ(which(frameAt(frames, start, next, 1.0 / 30.0 * 3.0)), 2);  // 0.1 s, as i / fps
  EXPECT_EQ(which(frameAt(frames, start, next, 0.149)), 2);             // never the next episode's
  EXPECT_EQ(which(frameAt(frames, next, INT64_MAX, 0.0)), 3);
  EXPECT_EQ(which(frameAt(frames, next, INT64_MAX, 10.0)), 4);
  // A camera that started after the episode: its first frame stands for the rows before it.
  EXPECT_EQ(which(frameAt(frames, start - 20'000'000, next, 0.0)), 0);
  // An episode without frames has none.
  EXPECT_EQ(frameAt(frames, start + 300'000'000, INT64_MAX, 0.0), nullptr);
}

TEST(FeatureStats, LargeValuesKeepTheirVarianceAndNanIsLeftOut) {
  // A row index near 1e12 varying by a few units: a sum of squares would lose the variance.
  FeatureStats stats(2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double rows[4][2] = {{1e12 + 1, 2.0}, {1e12 + 2, nan}, {1e12 + 3, 4.0}, {1e12 + 4, nan}};
  for (const auto& row : rows) {
    stats.add(row);
  }
  const nlohmann::json json = stats.json();
  EXPECT_DOUBLE_EQ(json["mean"][0].get<double>(), 1e12 + 2.5);
  EXPECT_NEAR(json["std"][0].get<double>(), std::sqrt(1.25), 1e-9);
  EXPECT_EQ(json["min"][0].get<double>(), 1e12 + 1);
  EXPECT_EQ(json["max"][0].get<double>(), 1e12 + 4);
  // The second dimension from its two numbers only.
  EXPECT_DOUBLE_EQ(json["mean"][1].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(json["std"][1].get<double>(), 1.0);
  EXPECT_EQ(json["count"], nlohmann::json::array({4}));

  FeatureStats empty(1);
  const double only_nan[1] = {nan};
  empty.add(only_nan);
  EXPECT_TRUE(empty.json()["mean"][0].is_null()) << "no number is made up for a NaN column";
}

sim::Image shade(int width, int height, std::uint8_t red, std::uint8_t green) {
  sim::Image image{width, height, {}};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.rgb.insert(image.rgb.end(), {red, green, static_cast<std::uint8_t>(4 * x)});
    }
  }
  return image;
}

TEST(PngSize, ReadFromTheHeaderAndRefusedForOtherBytes) {
  int width = 0;
  int height = 0;
  ASSERT_TRUE(pngSize(sim::encodePng(shade(40, 30, 1, 2)), width, height));
  EXPECT_EQ(width, 40);
  EXPECT_EQ(height, 30);
  EXPECT_FALSE(pngSize({0xFF, 0xD8, 0xFF, 0xE0}, width, height));  // a JPEG's start
  EXPECT_FALSE(pngSize({}, width, height));
}

/// A command's stdout; a test failure when it fails.
std::string run(const std::string& command) {
  const auto [status, out] = testing::runCommand(command);
  EXPECT_EQ(status, 0) << command;
  return out;
}

TEST(VideoEncoder, AFramePerPngInOrderAtTheRate) {
  const testing::ScratchDir folder("dataset_video_test");
  const std::filesystem::path video = folder.path() / "front.mp4";
  constexpr int kFrames = 9;
  {
    VideoEncoder encoder(video, 30.0);
    for (int k = 0; k < kFrames; ++k) {
      encoder.frame(sim::encodePng(shade(32, 24, static_cast<std::uint8_t>(25 * k), 128)));
    }
    encoder.finish();
    EXPECT_EQ(encoder.frames(), kFrames);
  }
  const std::string probe =
      run("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
          "stream=nb_read_frames,width,height,codec_name,r_frame_rate -of csv=p=0 '" +
          video.string() + "'");
  EXPECT_EQ(probe, "h264,32,24,30/1," + std::to_string(kFrames) + "\n");
  // Decoded, frame k is the red level 25 k it was given (lossy: within a few levels).
  const std::string raw =
      run("ffmpeg -v error -i '" + video.string() + "' -f rawvideo -pix_fmt rgb24 -");
  ASSERT_EQ(raw.size(), static_cast<std::size_t>(kFrames) * 32 * 24 * 3);
  for (int k = 0; k < kFrames; ++k) {
    const auto at = static_cast<std::size_t>(k) * 32 * 24 * 3 + (12 * 32 + 16) * 3;
    EXPECT_NEAR(static_cast<unsigned char>(raw[at]), 25 * k, 6) << "frame " << k;
    EXPECT_NEAR(static_cast<unsigned char>(raw[at + 1]), 128, 6) << "frame " << k;
  }
  EXPECT_FALSE(std::filesystem::exists(video.string() + ".ffmpeg.log"));
}

TEST(VideoEncoder, BytesThatAreNoPngFailWithFfmpegsOwnWords) {
  const testing::ScratchDir folder("dataset_video_test");
  VideoEncoder encoder(folder.path() / "broken.mp4", 30.0);
  const std::vector<std::uint8_t> garbage(4096, 0x42);
  try {
    for (int k = 0; k < 64; ++k) {  // ffmpeg may take a few before it gives up
      encoder.frame(garbage);
    }
    encoder.finish();
    FAIL() << "ffmpeg took bytes that are not a PNG";
  } catch (const std::runtime_error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("broken.mp4"), std::string::npos) << what;
    EXPECT_NE(what.find("ffmpeg"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace comply::exporter
