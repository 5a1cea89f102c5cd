// Each feature's statistics (see feature_stats.hpp).

#include "feature_stats.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ffmpeg_process.hpp"

namespace comply::exporter {

FeatureStats::FeatureStats(int width)
    : count_(static_cast<std::size_t>(width), 0),
      min_(static_cast<std::size_t>(width), std::numeric_limits<double>::infinity()),
      max_(static_cast<std::size_t>(width), -std::numeric_limits<double>::infinity()),
      mean_(static_cast<std::size_t>(width), 0.0),
      m2_(static_cast<std::size_t>(width), 0.0) {}

void FeatureStats::add(const double* row) {
  ++rows_;
  for (std::size_t d = 0; d < mean_.size(); ++d) {
    const double x = row[d];
    if (std::isnan(x)) {
      continue;
    }
    const double n = static_cast<double>(++count_[d]);
    const double delta = x - mean_[d];
    mean_[d] += delta / n;
    m2_[d] += delta * (x - mean_[d]);
    min_[d] = std::min(min_[d], x);
    max_[d] = std::max(max_[d], x);
  }
}

nlohmann::json FeatureStats::json() const {
  // A dimension that held only NaN has no statistics: null, not a made-up number.
  const auto values = [&](const std::vector<double>& of) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t d = 0; d < of.size(); ++d) {
      out.push_back(count_[d] > 0 ? nlohmann::json(of[d]) : nlohmann::json(nullptr));
    }
    return out;
  };
  std::vector<double> std_dev(m2_.size());
  for (std::size_t d = 0; d < m2_.size(); ++d) {
    std_dev[d] = count_[d] > 0 ? std::sqrt(m2_[d] / static_cast<double>(count_[d])) : 0.0;
  }
  return {{"min", values(min_)},
          {"max", values(max_)},
          {"mean", values(mean_)},
          {"std", values(std_dev)},
          {"count", {rows_}}};
}

nlohmann::json tableStats(const ParquetTable& table) {
  nlohmann::json out = nlohmann::json::object();
  const auto rows = static_cast<std::size_t>(table.rows());
  for (const ParquetTable::NumericColumn& column : table.numericColumns()) {
    const auto width = static_cast<std::size_t>(column.width);
    FeatureStats stats(column.width);
    std::vector<double> row(width);
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t d = 0; d < width; ++d) {
        const std::size_t at = r * width + d;
        row[d] = !column.int64s.empty()   ? static_cast<double>(column.int64s[at])
                 : !column.floats.empty() ? static_cast<double>(column.floats[at])
                                          : column.doubles[at];
      }
      stats.add(row.data());
    }
    out[std::string(column.name)] = stats.json();
  }
  return out;
}

nlohmann::json videoStats(const std::filesystem::path& video, int width_px, int height_px) {
  FfmpegProcess ffmpeg({"-hide_banner", "-nostats", "-loglevel", "error", "-i", video.string(),
                        "-f", "rawvideo", "-pix_fmt", "rgb24", "pipe:1"},
                       FfmpegProcess::Pipe::kFromStdout, video.string() + ".stats.log");
  const std::size_t frame_bytes = static_cast<std::size_t>(width_px) * height_px * 3;
  std::vector<std::uint8_t> frame(frame_bytes);
  // Whole numbers: the sums of 8-bit values and of their squares are exact in 64 bits.
  std::array<std::uint64_t, 3> sum{}, sum_squares{};
  std::array<int, 3> low{255, 255, 255}, high{0, 0, 0};
  std::uint64_t pixels = 0;
  std::int64_t frames = 0;
  for (std::size_t got; (got = readAll(ffmpeg.fd(), frame.data(), frame_bytes)) > 0;) {
    if (got != frame_bytes) {
      (void)ffmpeg.wait();
      throw std::runtime_error(video.string() + ": a decoded frame is not " +
                               std::to_string(width_px) + " x " + std::to_string(height_px));
    }
    for (std::size_t i = 0; i < frame_bytes; i += 3) {
      for (std::size_t c = 0; c < 3; ++c) {
        const int value = frame[i + c];
        sum[c] += static_cast<std::uint64_t>(value);
        sum_squares[c] += static_cast<std::uint64_t>(value * value);
        low[c] = std::min(low[c], value);
        high[c] = std::max(high[c], value);
      }
    }
    pixels += frame_bytes / 3;
    ++frames;
  }
  if (const std::string why = ffmpeg.wait(); !why.empty()) {
    throw std::runtime_error("statistics of " + video.string() + ": " + why);
  }
  if (pixels == 0) {
    throw std::runtime_error("statistics of " + video.string() + ": no frame decodes");
  }
  // LeRobot's images are 0 to 1, and their statistics per channel of shape (1, 1).
  const auto channels = [](const std::array<double, 3>& of) {
    return nlohmann::json{{{of[0]}}, {{of[1]}}, {{of[2]}}};
  };
  std::array<double, 3> min{}, max{}, mean{}, std_dev{};
  const auto n = static_cast<double>(pixels);
  for (std::size_t c = 0; c < 3; ++c) {
    const double m = static_cast<double>(sum[c]) / n;
    mean[c] = m / 255.0;
    std_dev[c] = std::sqrt(std::max(0.0, static_cast<double>(sum_squares[c]) / n - m * m)) / 255.0;
    min[c] = low[c] / 255.0;
    max[c] = high[c] / 255.0;
  }
  return {{"min", channels(min)},
          {"max", channels(max)},
          {"mean", channels(mean)},
          {"std", channels(std_dev)},
          {"count", {frames}}};
}

}  // namespace comply::exporter
