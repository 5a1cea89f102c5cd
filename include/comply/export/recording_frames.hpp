#pragma once
// One recording (comply sim --record, comply run --record) as one episode of frames at a fixed
// rate, the table LeRobot datasets train on (its data/*.parquet files): the recording's cycle
// records (channel `/<name>/cycle`) sampled at exactly t_i = i / fps from the episode's first
// record, each frame the cycle in force at t_i (the last at or before it).
//
// Columns (LeRobot's own first, then the observation and the action as comply records them;
// float32 lists, every row the same width):
//
//   timestamp              float32, i / fps [s]
//   frame_index            int64, i
//   episode_index, index, task_index
//                          int64: the episode, first_index + i, the task
//   observation.state      joint position [rad | m], dof
//   observation.velocity   joint velocity, dof
//   observation.effort     measured joint effort [N m | N], dof
//   observation.tcp_pose   measured TCP: x y z [m], qx qy qz qw, 7
//   observation.contact_wrench  the contact wrench, base frame, force first [N, N m], 6
//   action                 the reference in force: Cartesian x y z qx qy qz qw (7); joint q (dof)
//   action.stiffness       Cartesian: translational then rotational 3x3, row-major, task frame
//                          (18); joint: per joint (dof)
//   action.damping         the same shapes (Cartesian: the absolute-mode blocks)
//   action.damping_ratio   Cartesian only: per task axis x y z rx ry rz (ratio mode), 6
//   action.task_frame      Cartesian only: qx qy qz qw in the base frame, 4
//
// A cycle without a command in force (before the first) gives NaN actions: nothing is made up.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "comply/export/parquet_table.hpp"

namespace comply::exporter {

struct EpisodeFrames {
  ParquetTable table;
  std::int64_t frames = 0;
  int dof = 0;
  bool cartesian = true;
  std::vector<std::string> joint_names;
  double duration_s = 0.0;  ///< from the first cycle record to the last
  /// The first cycle record's stamp [ns]: frame i is at first_stamp_ns + i / fps.
  std::int64_t first_stamp_ns = 0;
};

/// The episodes of `recording`, each sampled at `fps` (> 0): a new one wherever the host's cycle
/// count starts again (Python's Sim records every episode after a reset into one file), numbered
/// from `first_episode_index`, their rows from `first_index` on. Throws std::runtime_error naming
/// the file when it cannot be read, has no cycle channel or no cycle record, a record does not
/// decode, goes back in time within an episode or changes the joints; std::invalid_argument for an
/// fps that is not positive.
std::vector<EpisodeFrames> recordingEpisodes(const std::filesystem::path& recording, double fps,
                                             std::int64_t first_episode_index,
                                             std::int64_t first_index, std::int64_t task_index);

/// recordingEpisodes() of a recording of one episode (std::runtime_error for more).
EpisodeFrames recordingFrames(const std::filesystem::path& recording, double fps,
                              std::int64_t episode_index, std::int64_t first_index,
                              std::int64_t task_index);

}  // namespace comply::exporter
