// A recording's cycle records sampled at i / fps (see recording_frames.hpp).

#include "comply/export/recording_frames.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "comply/record/mcap_reader.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/messages.hpp"

namespace comply::exporter {
namespace {

using transport::CycleRecordMessage;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// A record stamped within this of a frame's time is in force at it: the stamps are whole
// nanoseconds, i / fps is not.
constexpr double kStampTolerance_s = 1e-9;

/// The columns as they grow, frame by frame.
struct Columns {
  std::vector<std::int64_t> frame_index;
  std::vector<float> timestamp;
  std::vector<float> state, velocity, effort, tcp_pose, contact_wrench;
  std::vector<float> action, stiffness, damping, damping_ratio, task_frame;
};

template <typename Values>
void append(std::vector<float>& column, const Values& values) {
  for (const auto value : values) {
    column.push_back(static_cast<float>(value));
  }
}

/// A joint vector of `dof` entries; NaN for each where the record has none (a host without
/// effort readings), so that every row keeps the feature's width.
template <typename Values>
void appendJoints(std::vector<float>& column, const Values& values, int dof) {
  if (static_cast<int>(values.size()) == dof) {
    append(column, values);
  } else {
    column.insert(column.end(), static_cast<std::size_t>(dof), kNaN);
  }
}

/// A 3x3 block, row after row.
void appendRowMajor(std::vector<float>& column, const Eigen::Matrix3d& block) {
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      column.push_back(static_cast<float>(block(row, col)));
    }
  }
}

void appendQuaternion(std::vector<float>& column, const Eigen::Quaterniond& q) {
  append(column, std::array<double, 4>{q.x(), q.y(), q.z(), q.w()});
}

class FrameSampler {
 public:
  FrameSampler(double fps, int dof, bool cartesian) : fps_(fps), dof_(dof), cartesian_(cartesian) {}

  /// Frames whose time has come before a record at `time_s`, each from `in_force`.
  void until(double time_s, const CycleRecordMessage& in_force) {
    while (static_cast<double>(next_) / fps_ < time_s - kStampTolerance_s) {
      emit(in_force);
    }
  }
  /// The last record: frames up to its time (inclusive).
  void through(double time_s, const CycleRecordMessage& last) {
    while (static_cast<double>(next_) / fps_ <= time_s + kStampTolerance_s) {
      emit(last);
    }
  }
  Columns& columns() { return columns_; }
  [[nodiscard]] std::int64_t frames() const { return next_; }

 private:
  void emit(const CycleRecordMessage& record) {
    columns_.frame_index.push_back(next_);
    columns_.timestamp.push_back(static_cast<float>(static_cast<double>(next_) / fps_));
    const transport::ControllerStateMessage& s = record.state;
    append(columns_.state, s.position);  // the episode's joints, checked as it arrived
    appendJoints(columns_.velocity, s.velocity, dof_);
    appendJoints(columns_.effort, s.effort, dof_);
    append(columns_.tcp_pose, s.tcp_position);
    append(columns_.tcp_pose, s.tcp_orientation);
    append(columns_.contact_wrench, s.contact_wrench);
    if (cartesian_) {
      emitCartesian(record);
    } else {
      emitJoint(record);
    }
    ++next_;
  }

  void emitCartesian(const CycleRecordMessage& record) {
    if (record.cartesian_in_force.empty()) {
      columns_.action.insert(columns_.action.end(), 7, kNaN);
      columns_.stiffness.insert(columns_.stiffness.end(), 18, kNaN);
      columns_.damping.insert(columns_.damping.end(), 18, kNaN);
      columns_.damping_ratio.insert(columns_.damping_ratio.end(), 6, kNaN);
      columns_.task_frame.insert(columns_.task_frame.end(), 4, kNaN);
      return;
    }
    const CartesianCommand& c = record.cartesian_in_force.front().command;
    append(columns_.action, c.position);
    appendQuaternion(columns_.action, c.orientation);
    appendRowMajor(columns_.stiffness, c.stiffness_translational);
    appendRowMajor(columns_.stiffness, c.stiffness_rotational);
    appendRowMajor(columns_.damping, c.damping_translational);
    appendRowMajor(columns_.damping, c.damping_rotational);
    append(columns_.damping_ratio, c.damping_ratio);
    appendQuaternion(columns_.task_frame, c.task_frame);
  }

  void emitJoint(const CycleRecordMessage& record) {
    const auto width = static_cast<std::size_t>(dof_);
    if (record.joint_in_force.empty()) {
      columns_.action.insert(columns_.action.end(), width, kNaN);
      columns_.stiffness.insert(columns_.stiffness.end(), width, kNaN);
      columns_.damping.insert(columns_.damping.end(), width, kNaN);
      return;
    }
    const JointCommand& c = record.joint_in_force.front().command;
    appendJoints(columns_.action, c.position, dof_);
    appendJoints(columns_.stiffness, c.stiffness, dof_);
    appendJoints(columns_.damping, c.damping, dof_);
  }

  double fps_;
  int dof_;
  bool cartesian_;
  std::int64_t next_ = 0;
  Columns columns_;
};

/// The table of one episode's sampled frames.
void tabulate(Columns& columns, std::int64_t episode_index, std::int64_t first_index,
              std::int64_t task_index, EpisodeFrames& episode) {
  const auto frames = static_cast<std::size_t>(episode.frames);
  ParquetTable& table = episode.table;
  table.addFloat("timestamp", std::move(columns.timestamp));
  table.addInt64("frame_index", columns.frame_index);
  table.addInt64("episode_index", std::vector<std::int64_t>(frames, episode_index));
  std::vector<std::int64_t> index(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    index[i] = first_index + static_cast<std::int64_t>(i);
  }
  table.addInt64("index", std::move(index));
  table.addInt64("task_index", std::vector<std::int64_t>(frames, task_index));
  const int dof = episode.dof;
  table.addFloatList("observation.state", std::move(columns.state), dof);
  table.addFloatList("observation.velocity", std::move(columns.velocity), dof);
  table.addFloatList("observation.effort", std::move(columns.effort), dof);
  table.addFloatList("observation.tcp_pose", std::move(columns.tcp_pose), 7);
  table.addFloatList("observation.contact_wrench", std::move(columns.contact_wrench), 6);
  if (episode.cartesian) {
    table.addFloatList("action", std::move(columns.action), 7);
    table.addFloatList("action.stiffness", std::move(columns.stiffness), 18);
    table.addFloatList("action.damping", std::move(columns.damping), 18);
    table.addFloatList("action.damping_ratio", std::move(columns.damping_ratio), 6);
    table.addFloatList("action.task_frame", std::move(columns.task_frame), 4);
  } else {
    table.addFloatList("action", std::move(columns.action), dof);
    table.addFloatList("action.stiffness", std::move(columns.stiffness), dof);
    table.addFloatList("action.damping", std::move(columns.damping), dof);
  }
}

/// A recording's cycle records, in file order, into episodes: a new one wherever the host's cycle
/// count starts again (Python's Sim: at every reset).
class EpisodeSplitter {
 public:
  EpisodeSplitter(std::string name, double fps, std::int64_t first_episode_index,
                  std::int64_t first_index, std::int64_t task_index)
      : name_(std::move(name)),
        fps_(fps),
        first_episode_index_(first_episode_index),
        next_index_(first_index),
        task_index_(task_index) {}

  /// One record's bytes; after an error (error()) the rest are ignored.
  void add(std::span<const std::uint8_t> bytes) {
    if (!error_.empty()) {
      return;
    }
    const std::uint64_t record = records_++;
    const auto which = [&] { return name_ + ": cycle record " + std::to_string(record); };
    CycleRecordMessage cycle;
    if (!transport::decodeCdr(bytes, cycle)) {
      error_ = which() + " does not decode";
      return;
    }
    const transport::ControllerStateMessage& state = cycle.state;
    if (state.position.size() != state.joint_names.size() || state.position.empty()) {
      error_ = which() + " has " + std::to_string(state.position.size()) + " joint positions for " +
               std::to_string(state.joint_names.size()) + " joints";
      return;
    }
    if (previous_ && state.cycle <= previous_->state.cycle) {
      finish();
    }
    const std::int64_t time_ns = state.header.stamp.nanoseconds();
    if (!sampler_) {
      episode_.dof = static_cast<int>(state.position.size());
      episode_.cartesian = state.command_kind == transport::WireCommandKind::kCartesian;
      episode_.joint_names = state.joint_names;
      sampler_.emplace(fps_, episode_.dof, episode_.cartesian);
      first_ns_ = time_ns;
    } else if (time_ns < last_ns_) {
      error_ = which() + " is stamped before the one before it";
      return;
    } else if (state.joint_names != episode_.joint_names) {
      error_ = which() + " is of other joints than the episode's first";
      return;
    } else {
      sampler_->until(1e-9 * static_cast<double>(time_ns - first_ns_), *previous_);
    }
    last_ns_ = time_ns;
    previous_ = std::move(cycle);
  }

  /// The episode in progress, sampled to its last record, into episodes().
  void finish() {
    if (!sampler_) {
      return;
    }
    const double duration_s = 1e-9 * static_cast<double>(last_ns_ - first_ns_);
    sampler_->through(duration_s, *previous_);
    episode_.frames = sampler_->frames();
    episode_.duration_s = duration_s;
    episode_.first_stamp_ns = first_ns_;
    tabulate(sampler_->columns(),
             first_episode_index_ + static_cast<std::int64_t>(episodes_.size()), next_index_,
             task_index_, episode_);
    next_index_ += episode_.frames;
    episodes_.push_back(std::move(episode_));
    episode_ = EpisodeFrames{};
    sampler_.reset();
    previous_.reset();
  }

  [[nodiscard]] const std::string& error() const { return error_; }
  std::vector<EpisodeFrames>& episodes() { return episodes_; }

 private:
  std::string name_;
  double fps_;
  std::int64_t first_episode_index_;
  std::int64_t next_index_;
  std::int64_t task_index_;
  std::uint64_t records_ = 0;
  std::string error_;
  std::vector<EpisodeFrames> episodes_;
  // The episode in progress: its frames so far, its first and last record's times, its last.
  EpisodeFrames episode_;
  std::optional<FrameSampler> sampler_;
  std::optional<CycleRecordMessage> previous_;
  std::int64_t first_ns_ = 0;
  std::int64_t last_ns_ = 0;
};

/// The id of the recording's cycle channel; throws naming the file without exactly one.
std::uint16_t cycleChannel(const std::string& name) {
  std::optional<std::uint16_t> found;
  for (const record::McapChannelInfo& channel : record::readMcap(name).channels) {
    if (channel.topic.ends_with("/cycle") && channel.schema_name.ends_with("CycleRecord")) {
      if (found) {
        throw std::runtime_error(name + ": more than one cycle channel (" + channel.topic +
                                 "): one host's recording per file");
      }
      found = channel.id;
    }
  }
  if (!found) {
    throw std::runtime_error(name +
                             ": no cycle channel (/<name>/cycle, comply_msgs/CycleRecord): " +
                             "record with comply sim --record or comply run --record");
  }
  return *found;
}

}  // namespace

std::vector<EpisodeFrames> recordingEpisodes(const std::filesystem::path& recording, double fps,
                                             std::int64_t first_episode_index,
                                             std::int64_t first_index, std::int64_t task_index) {
  if (!(fps > 0.0) || !std::isfinite(fps)) {
    throw std::invalid_argument("the frame rate must be positive, not " + std::to_string(fps));
  }
  const std::string name = recording.string();
  // The channels first (a pass without messages), then the cycle channel's records.
  const std::uint16_t channel = cycleChannel(name);
  EpisodeSplitter splitter(name, fps, first_episode_index, first_index, task_index);
  (void)record::readMcap(name, [&](const record::McapMessageView& message) {
    if (message.channel_id == channel) {
      splitter.add(message.data);
    }
  });
  if (!splitter.error().empty()) {
    throw std::runtime_error(splitter.error());
  }
  splitter.finish();
  if (splitter.episodes().empty()) {
    throw std::runtime_error(name + ": no cycle record in the cycle channel");
  }
  return std::move(splitter.episodes());
}

EpisodeFrames recordingFrames(const std::filesystem::path& recording, double fps,
                              std::int64_t episode_index, std::int64_t first_index,
                              std::int64_t task_index) {
  std::vector<EpisodeFrames> episodes =
      recordingEpisodes(recording, fps, episode_index, first_index, task_index);
  if (episodes.size() != 1) {
    throw std::runtime_error(recording.string() + " holds " + std::to_string(episodes.size()) +
                             " episodes, not one");
  }
  return std::move(episodes.front());
}

}  // namespace comply::exporter
