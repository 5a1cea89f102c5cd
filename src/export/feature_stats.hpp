#pragma once
// Each feature's statistics, which LeRobot normalises a policy's inputs and outputs with
// (meta/stats.json): per dimension the min, max, mean and standard deviation, and the count.
// Private to the export module.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "comply/export/parquet_table.hpp"

namespace comply::exporter {

/// Per-dimension statistics of rows of `width` values, updated a row at a time (Welford's update,
/// so that the mean and variance of large values, a dataset's row index, keep their precision).
/// NaN values (an action before the first command) are left out of their dimension.
class FeatureStats {
 public:
  explicit FeatureStats(int width);
  void add(const double* row);
  /// {"min": [...], "max": [...], "mean": [...], "std": [...], "count": [n]}, the standard
  /// deviation of the population; n the rows added.
  [[nodiscard]] nlohmann::json json() const;

 private:
  std::int64_t rows_ = 0;
  std::vector<std::int64_t> count_;
  std::vector<double> min_, max_, mean_, m2_;
};

/// Every numeric column of `table` (strings left out), by name.
nlohmann::json tableStats(const ParquetTable& table);

/// An 8-bit RGB video's statistics per channel, on LeRobot's scale (0 to 1) and in its shape
/// (3 x 1 x 1), from every frame ffmpeg decodes of `video` (what a loader will see, the coding's
/// loss included). Throws std::runtime_error naming the file when ffmpeg fails or the frames are
/// not `width_px` x `height_px`.
nlohmann::json videoStats(const std::filesystem::path& video, int width_px, int height_px);

}  // namespace comply::exporter
