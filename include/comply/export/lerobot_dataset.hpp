#pragma once
// Recordings as a LeRobot dataset (format v3.0): each recording one episode of frames at a fixed
// rate (recording_frames.hpp), in the layout LeRobot reads:
//
//   data/chunk-000/file-000.parquet              every episode's frames, one after another
//   meta/info.json                               the format's version, fps, totals, the path
//                                                templates, every feature's dtype, shape, names
//   meta/stats.json                              every feature's min, max, mean, std, count (per
//                                                dimension; a camera's per channel, 0 to 1)
//   meta/tasks.parquet                           task_index, task
//   meta/episodes/chunk-000/file-000.parquet     per episode: its index, length, file and its
//                                                rows in the data file (dataset_from_index,
//                                                dataset_to_index), where its frames are in each
//                                                video (videos/<key>/from_timestamp, to_timestamp),
//                                                the recording it came from
//   videos/observation.images.<camera>/chunk-000/file-000.mp4
//                                                each camera a recording holds (a Sim's cameras):
//                                                every episode's frames, a frame per data row, at
//                                                i / fps, encoded by Debian's ffmpeg (H.264)
//
// A camera's frame for row i is the one in force at the row's time (the last taken at or before
// it), as for the cycle records. Not yet written: the episodes' own statistics columns and their
// `tasks` list column.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace comply::exporter {

struct LeRobotOptions {
  double fps = 30.0;
  std::string task = "comply recording";  ///< the one task every episode is given
  std::string robot_type;                 ///< info.json's robot_type ("" : null)
};

struct LeRobotSummary {
  std::int64_t episodes = 0;
  std::int64_t frames = 0;
  std::vector<std::filesystem::path> files;  ///< what was written
};

/// Writes the dataset into `folder` (made if missing; files of the same names are replaced).
/// Every recording must come from one kind of controller on the same joints, with the same
/// cameras. Throws
/// std::runtime_error naming the recording or file at fault, std::invalid_argument for options
/// out of range or no recording.
LeRobotSummary writeLeRobotDataset(const std::filesystem::path& folder,
                                   const std::vector<std::filesystem::path>& recordings,
                                   const LeRobotOptions& options);

}  // namespace comply::exporter
