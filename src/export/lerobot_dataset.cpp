// A LeRobot v3.0 dataset from recordings (see lerobot_dataset.hpp).

#include "comply/export/lerobot_dataset.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "comply/export/parquet_table.hpp"
#include "comply/export/recording_frames.hpp"
#include "dataset_videos.hpp"
#include "feature_stats.hpp"

namespace comply::exporter {
namespace {

constexpr std::int64_t kChunksSize = 1000;  // episodes per chunk folder, LeRobot's default

/// One feature of info.json.
nlohmann::json feature(const std::string& dtype, int width, const nlohmann::json& names) {
  return {{"dtype", dtype}, {"shape", {width}}, {"names", names}};
}

nlohmann::json features(const EpisodeFrames& first) {
  const nlohmann::json joints = first.joint_names;
  const nlohmann::json pose = {"x", "y", "z", "qx", "qy", "qz", "qw"};
  const nlohmann::json wrench = {"fx", "fy", "fz", "tx", "ty", "tz"};
  nlohmann::json out = {
      {"timestamp", feature("float32", 1, nullptr)},
      {"frame_index", feature("int64", 1, nullptr)},
      {"episode_index", feature("int64", 1, nullptr)},
      {"index", feature("int64", 1, nullptr)},
      {"task_index", feature("int64", 1, nullptr)},
      {"observation.state", feature("float32", first.dof, joints)},
      {"observation.velocity", feature("float32", first.dof, joints)},
      {"observation.effort", feature("float32", first.dof, joints)},
      {"observation.tcp_pose", feature("float32", 7, pose)},
      {"observation.contact_wrench", feature("float32", 6, wrench)},
  };
  if (first.cartesian) {
    nlohmann::json blocks = nlohmann::json::array();
    for (const char* block : {"translational", "rotational"}) {
      for (const char* row : {"x", "y", "z"}) {
        for (const char* col : {"x", "y", "z"}) {
          blocks.push_back(std::string(block) + "_" + row + col);
        }
      }
    }
    out["action"] = feature("float32", 7, pose);
    out["action.stiffness"] = feature("float32", 18, blocks);
    out["action.damping"] = feature("float32", 18, blocks);
    out["action.damping_ratio"] = feature("float32", 6, {"x", "y", "z", "rx", "ry", "rz"});
    out["action.task_frame"] = feature("float32", 4, {"qx", "qy", "qz", "qw"});
  } else {
    out["action"] = feature("float32", first.dof, joints);
    out["action.stiffness"] = feature("float32", first.dof, joints);
    out["action.damping"] = feature("float32", first.dof, joints);
  }
  return out;
}

/// A camera's feature: its frames are in a video, a frame per row.
nlohmann::json videoFeature(const CameraVideo& video, double fps) {
  return {{"dtype", "video"},
          {"shape", {video.height_px, video.width_px, 3}},
          {"names", {"height", "width", "channels"}},
          {"info",
           {{"video.height", video.height_px},
            {"video.width", video.width_px},
            {"video.codec", "h264"},
            {"video.pix_fmt", "yuv420p"},
            {"video.is_depth_map", false},
            {"video.fps", fps},
            {"video.channels", 3},
            {"has_audio", false}}}};
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

/// meta/episodes: each episode's index, length, its rows in the one data file, the recording.
void writeEpisodes(const std::filesystem::path& path, const std::vector<EpisodeFrames>& episodes,
                   const std::vector<std::string>& sources,
                   const std::vector<CameraVideo>& videos) {
  std::vector<std::int64_t> index, length, zeros(episodes.size(), 0), from, to;
  std::int64_t row = 0;
  for (std::size_t e = 0; e < episodes.size(); ++e) {
    index.push_back(static_cast<std::int64_t>(e));
    length.push_back(episodes[e].frames);
    from.push_back(row);
    row += episodes[e].frames;
    to.push_back(row);
  }
  ParquetTable table;
  table.addInt64("episode_index", index);
  table.addInt64("length", length);
  table.addInt64("data/chunk_index", zeros);
  table.addInt64("data/file_index", zeros);
  table.addInt64("dataset_from_index", from);
  table.addInt64("dataset_to_index", to);
  table.addInt64("meta/episodes/chunk_index", zeros);
  table.addInt64("meta/episodes/file_index", zeros);
  for (const CameraVideo& video : videos) {
    const std::string prefix = "videos/" + video.key + "/";
    table.addInt64(prefix + "chunk_index", zeros);
    table.addInt64(prefix + "file_index", zeros);
    table.addDouble(prefix + "from_timestamp", video.from_s);
    table.addDouble(prefix + "to_timestamp", video.to_s);
  }
  table.addString("comply/recording", sources);
  table.write(path);
}

}  // namespace

namespace {

/// Every recording's episodes, checked to be of one shape, numbered on from each other; their
/// camera frames into `videos` as they are read.
std::vector<EpisodeFrames> readEpisodes(const std::vector<std::filesystem::path>& recordings,
                                        double fps, DatasetVideos& videos,
                                        std::vector<std::string>& sources) {
  std::vector<EpisodeFrames> episodes;
  std::int64_t frames = 0;
  for (const std::filesystem::path& recording : recordings) {
    std::vector<EpisodeFrames> more =
        recordingEpisodes(recording, fps, static_cast<std::int64_t>(episodes.size()), frames, 0);
    videos.add(recording, more);
    for (EpisodeFrames& episode : more) {
      const EpisodeFrames& first = episodes.empty() ? episode : episodes.front();
      if (episode.cartesian != first.cartesian || episode.joint_names != first.joint_names) {
        throw std::runtime_error(recording.string() + " is of another controller " +
                                 "or other joints than " + recordings.front().string() +
                                 ": a dataset's frames all have one shape");
      }
      frames += episode.frames;
      sources.push_back(recording.filename().string());
      episodes.push_back(std::move(episode));
    }
  }
  return episodes;
}

nlohmann::json info(const LeRobotOptions& options, const std::vector<EpisodeFrames>& episodes,
                    std::int64_t frames, const std::vector<CameraVideo>& videos) {
  const auto episode_count = static_cast<std::int64_t>(episodes.size());
  nlohmann::json all = features(episodes.front());
  for (const CameraVideo& video : videos) {
    all[video.key] = videoFeature(video, options.fps);
  }
  return {
      {"codebase_version", "v3.0"},
      {"robot_type",
       options.robot_type.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.robot_type)},
      {"total_episodes", episode_count},
      {"total_frames", frames},
      {"total_tasks", 1},
      {"chunks_size", kChunksSize},
      {"data_files_size_in_mb", 100},
      {"video_files_size_in_mb", 500},
      {"fps", options.fps == std::floor(options.fps)
                  ? nlohmann::json(static_cast<std::int64_t>(options.fps))
                  : nlohmann::json(options.fps)},
      {"splits", {{"train", "0:" + std::to_string(episode_count)}}},
      {"data_path", "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"},
      {"video_path", videos.empty() ? nlohmann::json(nullptr)
                                    : nlohmann::json("videos/{video_key}/chunk-{chunk_index:03d}/"
                                                     "file-{file_index:03d}.mp4")},
      {"features", all},
  };
}

/// meta/tasks.parquet: task_index and the task's text, which pandas reads as the table's index
/// (the footer's "pandas" metadata, pandas' own format for it), as LeRobot's writer leaves it and
/// its loader takes a task's text from; its path.
std::filesystem::path writeTasks(const std::filesystem::path& folder, const std::string& task) {
  ParquetTable tasks;
  tasks.addInt64("task_index", {0});
  tasks.addString("task", {task});
  const auto column = [](const char* name, const char* pandas_type, const char* numpy_type) {
    return nlohmann::json{{"name", name},
                          {"field_name", name},
                          {"pandas_type", pandas_type},
                          {"numpy_type", numpy_type},
                          {"metadata", nullptr}};
  };
  const nlohmann::json pandas = {
      {"index_columns", {"task"}},
      {"column_indexes",
       {{{"name", nullptr},
         {"field_name", nullptr},
         {"pandas_type", "unicode"},
         {"numpy_type", "object"},
         {"metadata", {{"encoding", "UTF-8"}}}}}},
      {"columns", {column("task_index", "int64", "int64"), column("task", "unicode", "object")}},
      {"creator", {{"library", "comply"}, {"version", "1"}}},
      {"pandas_version", "1.5.3"}};
  tasks.addMetadata("pandas", pandas.dump());
  const std::filesystem::path file = folder / "meta" / "tasks.parquet";
  tasks.write(file);
  return file;
}

/// meta/stats.json: every numeric column's statistics and every camera's; its path.
std::filesystem::path writeStats(const std::filesystem::path& folder, const ParquetTable& data,
                                 const std::vector<CameraVideo>& videos) {
  nlohmann::json stats = tableStats(data);
  for (const CameraVideo& video : videos) {
    stats[video.key] = videoStats(folder / video.file, video.width_px, video.height_px);
  }
  const std::filesystem::path file = folder / "meta" / "stats.json";
  writeText(file, stats.dump(4) + "\n");
  return file;
}

}  // namespace

LeRobotSummary writeLeRobotDataset(const std::filesystem::path& folder,
                                   const std::vector<std::filesystem::path>& recordings,
                                   const LeRobotOptions& options) {
  if (recordings.empty()) {
    throw std::invalid_argument("no recording to export");
  }
  DatasetVideos videos(folder, options.fps);
  std::vector<std::string> sources;  // the recording of each episode
  std::vector<EpisodeFrames> episodes = readEpisodes(recordings, options.fps, videos, sources);
  videos.finish();
  std::int64_t frames = 0;
  for (const EpisodeFrames& episode : episodes) {
    frames += episode.frames;
  }

  const nlohmann::json metadata = info(options, episodes, frames, videos.cameras());
  // The frames of every episode, one after the other: each episode's columns appended.
  ParquetTable data = std::move(episodes.front().table);
  for (std::size_t e = 1; e < episodes.size(); ++e) {
    data.append(episodes[e].table);
  }
  const std::filesystem::path data_file = folder / "data" / "chunk-000" / "file-000.parquet";
  const std::filesystem::path episodes_file =
      folder / "meta" / "episodes" / "chunk-000" / "file-000.parquet";
  std::filesystem::create_directories(data_file.parent_path());
  std::filesystem::create_directories(episodes_file.parent_path());
  data.write(data_file);
  writeEpisodes(episodes_file, episodes, sources, videos.cameras());

  const std::filesystem::path tasks_file = writeTasks(folder, options.task);

  const std::filesystem::path info_file = folder / "meta" / "info.json";
  writeText(info_file, metadata.dump(4) + "\n");
  const std::filesystem::path stats_file = writeStats(folder, data, videos.cameras());
  LeRobotSummary summary{static_cast<std::int64_t>(episodes.size()),
                         frames,
                         {data_file, info_file, stats_file, tasks_file, episodes_file}};
  for (const CameraVideo& video : videos.cameras()) {
    summary.files.push_back(folder / video.file);
  }
  return summary;
}

}  // namespace comply::exporter
