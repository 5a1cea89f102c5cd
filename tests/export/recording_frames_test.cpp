// A recording sampled into frames (recording_frames.hpp): 0.8 s of a simulated FR3 stepping
// 3 cm at 0.5 s, recorded by `comply sim --record`, exported at 30 frames per second and read back
// by hyparquet (tests/export/read_parquet.mjs): as many rows as the run has frames, timestamps
// exactly i / fps, and the state, the action and the gains of each row those of the cycle in force
// at i / fps, found here in the recording by comply's MCAP reader.

#include "comply/export/recording_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "comply/export/lerobot_dataset.hpp"
#include "comply/record/mcap_reader.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/messages.hpp"
#include "read_parquet.hpp"
#include "scratch.hpp"

namespace comply::exporter {
namespace {

using test::readWithHyparquet;

const std::string kSourceDir = COMPLY_SOURCE_DIR;
const std::string kComply = COMPLY_CLI;

/// Every cycle record of `path`, in order, with its time from the first [s].
std::vector<std::pair<double, transport::CycleRecordMessage>> cycles(
    const std::filesystem::path& path) {
  std::uint16_t channel = 0;
  for (const record::McapChannelInfo& info : record::readMcap(path.string()).channels) {
    if (info.topic.ends_with("/cycle")) {
      channel = info.id;
    }
  }
  std::vector<std::pair<double, transport::CycleRecordMessage>> out;
  (void)record::readMcap(path.string(), [&](const record::McapMessageView& message) {
    if (message.channel_id != channel) {
      return;
    }
    transport::CycleRecordMessage cycle;
    EXPECT_TRUE(transport::decodeCdr(message.data, cycle));
    const auto& stamp = cycle.state.header.stamp;
    out.emplace_back(static_cast<double>(stamp.sec) + 1e-9 * stamp.nanosec, cycle);
  });
  const double first_s = out.front().first;
  for (auto& entry : out) {
    entry.first -= first_s;
  }
  return out;
}

std::vector<float> floats(const nlohmann::json& values) {
  std::vector<float> out;
  for (const nlohmann::json& value : values) {
    out.push_back(value.is_null() ? NAN : static_cast<float>(value.get<double>()));
  }
  return out;
}

class RecordingFrames : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new testing::ScratchDir("frames");
    const std::filesystem::path dir = scratch_->path();
    recording_ = dir / "run.mcap";
    const std::string command = kComply + " sim --robot fr3 --config " + kSourceDir +
                                "/config/sim/cartesian_impedance.yaml --task " + kSourceDir +
                                "/examples/sim/step_response.yaml --duration 0.8 --out '" +
                                (dir / "out").string() + "' --no-plot --snapshot-every 0 " +
                                "--record '" + recording_.string() + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  static void TearDownTestSuite() {
    delete scratch_;
    scratch_ = nullptr;
  }
  static testing::ScratchDir* scratch_;
  static std::filesystem::path recording_;
};
testing::ScratchDir* RecordingFrames::scratch_ = nullptr;
std::filesystem::path RecordingFrames::recording_;

TEST_F(RecordingFrames, EachRowIsTheCycleInForceAtExactlyIOverFps) {
  constexpr double kFps = 30.0;
  const EpisodeFrames episode = recordingFrames(recording_, kFps, 2, 100, 0);
  const auto recorded = cycles(recording_);
  ASSERT_GT(recorded.size(), 400U);
  EXPECT_EQ(episode.dof, 7);
  EXPECT_TRUE(episode.cartesian);
  EXPECT_DOUBLE_EQ(episode.duration_s, recorded.back().first);
  // Frames at 0, 1/30, ... up to the last record's time.
  const auto expected_frames = static_cast<std::int64_t>(std::floor(episode.duration_s * kFps)) + 1;
  EXPECT_EQ(episode.frames, expected_frames);
  const std::filesystem::path file = scratch_->path() / "episode.parquet";
  episode.table.write(file);

  const nlohmann::json read = readWithHyparquet(file);
  ASSERT_FALSE(read.is_null());
  ASSERT_EQ(read["num_rows"], expected_frames);
  const nlohmann::json& rows = read["rows"];
  std::size_t cycle = 0;
  for (std::int64_t i = 0; i < expected_frames; ++i) {
    const nlohmann::json& row = rows[static_cast<std::size_t>(i)];
    const double t_s = static_cast<double>(i) / kFps;
    EXPECT_EQ(static_cast<float>(row["timestamp"].get<double>()), static_cast<float>(t_s)) << i;
    EXPECT_EQ(row["frame_index"].get<std::string>(), std::to_string(i));
    EXPECT_EQ(row["index"].get<std::string>(), std::to_string(100 + i));
    EXPECT_EQ(row["episode_index"].get<std::string>(), "2");
    // The cycle in force: the last recorded at or before t_s.
    while (cycle + 1 < recorded.size() && recorded[cycle + 1].first <= t_s + 1e-9) {
      ++cycle;
    }
    const transport::CycleRecordMessage& in_force = recorded[cycle].second;
    ASSERT_EQ(in_force.cartesian_in_force.size(), 1U) << i;
    const CartesianCommand& command = in_force.cartesian_in_force.front().command;
    const std::vector<float> state = floats(row["observation.state"]);
    ASSERT_EQ(state.size(), 7U);
    for (std::size_t j = 0; j < 7; ++j) {
      EXPECT_EQ(state[j], static_cast<float>(in_force.state.position[j])) << i << ", " << j;
    }
    const std::vector<float> action = floats(row["action"]);
    ASSERT_EQ(action.size(), 7U);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(action[static_cast<std::size_t>(k)], static_cast<float>(command.position[k]));
    }
    EXPECT_EQ(action[6], static_cast<float>(command.orientation.w()));
    const std::vector<float> stiffness = floats(row["action.stiffness"]);
    ASSERT_EQ(stiffness.size(), 18U);
    EXPECT_EQ(stiffness[0], static_cast<float>(command.stiffness_translational(0, 0)));
    EXPECT_EQ(stiffness[1], static_cast<float>(command.stiffness_translational(0, 1)));
    EXPECT_EQ(stiffness[13], static_cast<float>(command.stiffness_rotational(1, 1)));
    EXPECT_GT(stiffness[0], 0.0F) << "a law in force has stiffness";
    const std::vector<float> ratio = floats(row["action.damping_ratio"]);
    ASSERT_EQ(ratio.size(), 6U);
    EXPECT_EQ(ratio[0], static_cast<float>(command.damping_ratio[0]));
    const std::vector<float> frame = floats(row["action.task_frame"]);
    ASSERT_EQ(frame.size(), 4U);
    EXPECT_EQ(frame[3], static_cast<float>(command.task_frame.w()));
  }
  // The step at 0.5 s moved the reference 3 cm along x.
  EXPECT_NEAR(floats(rows.back()["action"])[0] - floats(rows.front()["action"])[0], 0.03, 1e-6);
}

TEST_F(RecordingFrames, RefusesARateThatIsNotPositiveAndAFileWithoutCycles) {
  EXPECT_THROW((void)recordingFrames(recording_, 0.0, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW((void)recordingFrames(recording_, -30.0, 0, 0, 0), std::invalid_argument);
  const std::filesystem::path not_mcap = scratch_->path() / "not.mcap";
  std::ofstream(not_mcap) << "not a recording";
  EXPECT_ANY_THROW((void)recordingFrames(not_mcap, 30.0, 0, 0, 0));
}

TEST_F(RecordingFrames, TwoRecordingsAreTwoEpisodesOfOneLeRobotDataset) {
  const std::filesystem::path folder = scratch_->path() / "dataset";
  const std::string command = kComply + " export --lerobot '" + folder.string() + "' '" +
                              recording_.string() + "' '" + recording_.string() +
                              "' --fps 10 --task 'step 3 cm' --robot-type fr3 2>&1";
  const auto [status, text] = testing::runCommand(command);
  ASSERT_EQ(status, 0) << text;
  // 0.8 s at 10 fps: frames at 0, 0.1, ... up to the last cycle's stamp, in both episodes.
  const double duration_s = cycles(recording_).back().first;
  const auto per = static_cast<std::size_t>(std::floor(duration_s * 10.0 + 1e-9)) + 1;
  const std::size_t total = 2 * per;
  EXPECT_NE(text.find("2 episode(s), " + std::to_string(total) + " frames at 10 fps"),
            std::string::npos)
      << text;

  std::ifstream info_file(folder / "meta" / "info.json");
  const nlohmann::json info = nlohmann::json::parse(info_file);
  EXPECT_EQ(info["codebase_version"], "v3.0");
  EXPECT_EQ(info["robot_type"], "fr3");
  EXPECT_EQ(info["fps"], 10);
  EXPECT_EQ(info["total_episodes"], 2);
  EXPECT_EQ(info["total_frames"], total);
  EXPECT_EQ(info["splits"]["train"], "0:2");
  EXPECT_EQ(info["features"]["observation.state"]["shape"], nlohmann::json::array({7}));
  EXPECT_EQ(info["features"]["observation.state"]["names"][0], "fr3_joint1");
  EXPECT_EQ(info["features"]["action.stiffness"]["shape"], nlohmann::json::array({18}));
  EXPECT_EQ(info["features"]["action.task_frame"]["dtype"], "float32");

  const nlohmann::json data = readWithHyparquet(folder / "data" / "chunk-000" / "file-000.parquet");
  ASSERT_FALSE(data.is_null());
  ASSERT_EQ(data["num_rows"], total);
  for (std::size_t row = 0; row < total; ++row) {
    const nlohmann::json& frame = data["rows"][row];
    EXPECT_EQ(frame["index"].get<std::string>(), std::to_string(row));
    EXPECT_EQ(frame["episode_index"].get<std::string>(), row < per ? "0" : "1");
    EXPECT_EQ(frame["frame_index"].get<std::string>(), std::to_string(row % per));
    EXPECT_EQ(static_cast<float>(frame["timestamp"].get<double>()),
              static_cast<float>(static_cast<double>(row % per) / 10.0));
  }
  // The same recording twice: the same frames twice.
  EXPECT_EQ(data["rows"][3]["action"], data["rows"][per + 3]["action"]);
  EXPECT_EQ(data["rows"][3]["action.stiffness"], data["rows"][per + 3]["action.stiffness"]);

  const nlohmann::json episodes =
      readWithHyparquet(folder / "meta" / "episodes" / "chunk-000" / "file-000.parquet");
  ASSERT_FALSE(episodes.is_null());
  ASSERT_EQ(episodes["num_rows"], 2);
  EXPECT_EQ(episodes["rows"][1]["dataset_from_index"], std::to_string(per));
  EXPECT_EQ(episodes["rows"][1]["dataset_to_index"], std::to_string(total));
  EXPECT_EQ(episodes["rows"][1]["length"], std::to_string(per));
  EXPECT_EQ(episodes["rows"][1]["comply/recording"], "run.mcap");
  const nlohmann::json tasks = readWithHyparquet(folder / "meta" / "tasks.parquet");
  ASSERT_FALSE(tasks.is_null());
  EXPECT_EQ(tasks["rows"][0]["task"], "step 3 cm");
  // pandas reads the task's text as the index (its own metadata format), as LeRobot's loader
  // expects: the descriptor names a column that is there, and every column is described.
  const nlohmann::json pandas =
      nlohmann::json::parse(tasks["key_value_metadata"]["pandas"].get<std::string>());
  EXPECT_EQ(pandas["index_columns"], nlohmann::json::array({"task"}));
  ASSERT_EQ(pandas["columns"].size(), 2U);
  EXPECT_EQ(pandas["columns"][0]["field_name"], "task_index");
  EXPECT_EQ(pandas["columns"][1]["field_name"], "task");
  EXPECT_EQ(pandas["columns"][1]["pandas_type"], "unicode");
  EXPECT_TRUE(tasks["rows"][0].contains("task"));
}

TEST_F(RecordingFrames, TheCommandRefusesWhatIsNotARecordingWithTheReason) {
  const std::filesystem::path not_mcap = scratch_->path() / "notes.mcap";
  std::ofstream(not_mcap) << "not a recording";
  const auto [status, text] = testing::runCommand(kComply + " export --lerobot '" +
                                                  (scratch_->path() / "refused").string() + "' '" +
                                                  not_mcap.string() + "' 2>&1");
  EXPECT_EQ(status, 2) << text;
  EXPECT_NE(text.find("notes.mcap"), std::string::npos) << text;
}

}  // namespace
}  // namespace comply::exporter
