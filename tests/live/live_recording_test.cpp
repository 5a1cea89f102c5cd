// `comply run --record` with a client: the file holds exactly one cycle record per control cycle
// (the run's length is fixed by --duration), one command record per command the host received
// and one outcome per command, nothing dropped; an independent reader (Node's @mcap/core with
// rosmsg2-serialization, tests/record/read_mcap.mjs) decodes the commands to what this test sent.
// A host killed with SIGKILL mid-recording leaves a file whose complete chunks read.
//
// COMPLY_RECORD_SECONDS sets the run's length (default 4 s; the `long` test runs a minute).

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "comply/record/mcap_reader.hpp"
#include "live_harness.hpp"
#include "live_support.hpp"
#include "scratch.hpp"

namespace comply::live_test {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return scratchFile(name);
}

double recordSeconds() {
  const char* text = std::getenv("COMPLY_RECORD_SECONDS");
  return text != nullptr ? std::atof(text) : 4.0;
}

/// builtin_interfaces/Time at the start of a CDR message (a command's header.stamp, an
/// outcome's stamp): after the 4-byte encapsulation header, sec then nanosec.
std::int64_t leadingStamp(std::span<const std::uint8_t> cdr) {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::memcpy(&sec, cdr.data() + 4, 4);
  std::memcpy(&nanosec, cdr.data() + 8, 4);
  return transport::Stamp{sec, nanosec}.nanoseconds();
}

/// ControllerState.cycle of a CycleRecord: after header.stamp (8), header.frame_id (uint32 length
/// and bytes), state and command_kind (2 octets), aligned to 8.
std::uint64_t cycleIndex(std::span<const std::uint8_t> cdr) {
  std::uint32_t frame_length = 0;
  std::memcpy(&frame_length, cdr.data() + 4 + 8, 4);
  std::size_t offset = 8 + 4 + frame_length + 2;  // from the byte after the encapsulation header
  offset = (offset + 7) / 8 * 8;
  std::uint64_t cycle = 0;
  std::memcpy(&cycle, cdr.data() + 4 + offset, 8);
  return cycle;
}

struct Channels {
  std::map<std::string, std::uint64_t> counts;
  std::vector<std::uint64_t> cycles;           // ControllerState.cycle of every cycle record
  std::multiset<std::int64_t> command_stamps;  // both command topics
  std::multiset<std::int64_t> outcome_stamps;
  std::map<std::string, std::string> recording;  // the comply_recording metadata
  record::McapContents contents;
};

Channels readRecording(const fs::path& path) {
  Channels channels;
  std::map<std::uint16_t, std::string> topics;
  channels.contents = record::readMcap(path.string());
  for (const auto& channel : channels.contents.channels) {
    topics[channel.id] = channel.topic;
  }
  record::readMcap(path.string(), [&](const record::McapMessageView& m) {
    const std::string& topic = topics.at(m.channel_id);
    ++channels.counts[topic];
    if (topic.ends_with("/cycle")) {
      channels.cycles.push_back(cycleIndex(m.data));
    } else if (topic.ends_with("_command")) {
      channels.command_stamps.insert(leadingStamp(m.data));
    } else if (topic.ends_with("/outcome")) {
      channels.outcome_stamps.insert(leadingStamp(m.data));
    }
  });
  for (const auto& [name, map] : channels.contents.metadata) {
    if (name == "comply_recording") {
      channels.recording = map;
    }
  }
  return channels;
}

/// tests/record/read_mcap.mjs on `path`; null JSON when Node or its packages are missing.
nlohmann::json readWithNode(const fs::path& path, int messages) {
  const std::string command = "node " + kSourceDir + "/tests/record/read_mcap.mjs '" +
                              path.string() + "' --messages " + std::to_string(messages);
  const auto [status, text] = testing::runCommand(command);
  if (status != 0 || text.empty()) {
    ADD_FAILURE() << "read_mcap.mjs failed (exit " << status << "): run scripts/install-deps.sh "
                  << "to install Node's packages";
    return nullptr;
  }
  return nlohmann::json::parse(text);
}

/// `comply inspect` on `path`: its exit code and what it printed.
std::pair<int, std::string> inspect(const fs::path& path) {
  return testing::runCommand(kComply + " inspect '" + path.string() + "' 2>&1");
}

bool nodeAvailable() {
  return std::system("node --version > /dev/null 2>&1") == 0;
}

constexpr int kStiffnessChange = 150;  // the command (at 100 Hz) that changes the stiffness

TEST_P(LiveHostOn, RecordsEveryCycleCommandAndOutcome) {
  const double seconds = recordSeconds();
  const fs::path path = scratch(GetParam() + "_run.mcap");
  host_->setRecording(path.string(), seconds);
  const auto started = Clock::now();
  host_->start("rec_" + GetParam());
  ASSERT_TRUE(host_->connect(1, 7));
  const auto state = host_->state(5s);
  ASSERT_TRUE(state.has_value());
  // One chunk that holds the pose, played before the commands: its timing record has a channel
  // of its own (a late chunk, refused, has none).
  ASSERT_TRUE(host_->connectChunks(1));
  transport::CartesianChunkMessage chunk;
  chunk.header.stamp = transport::Stamp::now();
  for (int k = 0; k < 3; ++k) {
    chunk.chunk.waypoints.push_back(
        {chunk.header.stamp.seconds() + 0.02 * (k + 1),
         poseCommand(*state, Eigen::Vector3d::Zero(), chunk.header.stamp).command});
  }
  chunk.chunk.observation_s = chunk.header.stamp.seconds();
  ASSERT_TRUE(host_->send(chunk, 1));
  ASSERT_TRUE(host_->poll(5s, [&](const auto&) {
    return host_->outcomes().count(chunk.header.stamp.nanoseconds()) > 0;
  }));
  ASSERT_EQ(host_->outcomes()[chunk.header.stamp.nanoseconds()].front().outcome,
            transport::Outcome::kApplied);

  // Commands at 100 Hz until 0.5 s before the host stops: a 1 cm circle in x-y, every 10th
  // stamped in the past (rejected as stale), so both outcomes are in the file.
  std::vector<transport::CartesianCommandMessage> sent;
  const auto end = started + std::chrono::duration<double>(seconds - 0.5);
  auto next = Clock::now();
  for (int i = 0; Clock::now() < end; ++i) {
    const double phase = 0.01 * i;
    const Eigen::Vector3d offset(0.01 * std::sin(phase), 0.01 * (1.0 - std::cos(phase)), 0.0);
    transport::Stamp stamp = transport::Stamp::now();
    if (i % 10 == 9) {
      stamp = transport::Stamp::fromNanoseconds(stamp.nanoseconds() - 1'000'000'000);
    }
    sent.push_back(poseCommand(*state, offset, stamp));
    if (i == kStiffnessChange) {
      // One command changes the gains: the cycle records must show the change from the cycle
      // that took it on (the command in force travels in the lane only when it changes).
      sent.back().command.fields = sent.back().command.fields | CommandField::kStiffness;
      sent.back().command.stiffness_translational = Eigen::Vector3d(2345, 2345, 1234).asDiagonal();
      sent.back().command.stiffness_rotational = Eigen::Vector3d(55, 55, 55).asDiagonal();
    }
    ASSERT_TRUE(host_->send(sent.back(), 1));
    next += 10ms;
    std::this_thread::sleep_until(next);
  }
  ASSERT_TRUE(host_->poll(5s, [&](const auto&) {
    return host_->outcomes().count(sent.back().header.stamp.nanoseconds()) > 0;
  }));
  const std::uint64_t received = host_->last().commands_received;
  // The diagnostics name the recording and its drops while it runs.
  EXPECT_EQ(host_->last().recording, path.string());
  EXPECT_EQ(host_->last().records_dropped, 0U);
  // The host stops by itself after --duration (its set-up comes first): stopping it earlier
  // would cut the run short of its cycles.
  std::this_thread::sleep_until(started + std::chrono::duration<double>(seconds + 2.0));
  ASSERT_EQ(host_->stop(), 0);

  const Channels channels = readRecording(path);
  const std::string prefix = "/rec_" + GetParam();
  EXPECT_TRUE(channels.contents.complete) << channels.contents.stopped;
  // Exactly one cycle record per cycle, in order, none missing.
  const auto cycles = static_cast<std::uint64_t>(std::llround(seconds * 1000.0));
  ASSERT_EQ(channels.counts.at(prefix + "/cycle"), cycles);
  for (std::uint64_t i = 0; i < cycles; ++i) {
    ASSERT_EQ(channels.cycles[i], i);
  }
  // Every command sent is recorded, and has its outcome; the handshake's no-ops too.
  for (const auto& message : sent) {
    EXPECT_EQ(channels.command_stamps.count(message.header.stamp.nanoseconds()), 1U);
    EXPECT_EQ(channels.outcome_stamps.count(message.header.stamp.nanoseconds()), 1U);
  }
  EXPECT_GE(channels.command_stamps.size() + channels.counts.at(prefix + "/cartesian_chunk"),
            received);
  // The chunks' outcomes besides (the late one connectChunks() sent, the one played).
  EXPECT_EQ(channels.outcome_stamps.size(),
            channels.command_stamps.size() + channels.counts.at(prefix + "/cartesian_chunk"));
  EXPECT_EQ(channels.counts.at(prefix + "/cartesian_chunk"), 2U);
  EXPECT_EQ(channels.counts.at(prefix + "/chunk_timing"), 1U);
  EXPECT_EQ(channels.recording.at("records_dropped"), "0");
  // A live host's full lane drops (and counts): its control thread never waits for the disk.
  EXPECT_EQ(channels.recording.at("when_full"), "drop");
  EXPECT_GT(channels.counts.at(prefix + "/diagnostics"), 0U);
  // `comply inspect` lists the same counts and the drops.
  const auto [inspect_code, inspect_text] = inspect(path);
  EXPECT_EQ(inspect_code, 0) << inspect_text;
  EXPECT_NE(inspect_text.find(prefix + "/cycle"), std::string::npos) << inspect_text;
  EXPECT_NE(inspect_text.find(prefix + "/chunk_timing"), std::string::npos) << inspect_text;
  EXPECT_NE(inspect_text.find(std::to_string(cycles)), std::string::npos) << inspect_text;
  EXPECT_NE(inspect_text.find("dropped records: 0"), std::string::npos) << inspect_text;
  std::cerr << "recorded " << channels.contents.messages << " messages in "
            << fs::file_size(path) / 1000 << " kB; writer thread CPU "
            << channels.recording.at("writer_cpu_s") << " s for " << seconds << " s\n";

  if (!nodeAvailable()) {
    GTEST_SKIP() << "no node: the independent reader's check did not run";
  }
  const nlohmann::json node = readWithNode(path, 100000);
  ASSERT_FALSE(node.is_null());
  EXPECT_FALSE(node.at("truncated").get<bool>());
  const nlohmann::json& statistics = node.at("summary").at("statistics");
  EXPECT_EQ(std::stoull(statistics.at("message_count").get<std::string>()),
            channels.contents.messages);
  EXPECT_EQ(node.at("counts").at(prefix + "/cycle").get<std::uint64_t>(), cycles);
  // The decoded commands are what was sent, field for field where this test set them.
  std::map<std::int64_t, const transport::CartesianCommandMessage*> by_stamp;
  for (const auto& message : sent) {
    by_stamp[message.header.stamp.nanoseconds()] = &message;
  }
  std::size_t matched = 0;
  for (const nlohmann::json& entry : node.at("messages").at(prefix + "/cartesian_command")) {
    const nlohmann::json& data = entry.at("data");
    const transport::Stamp stamp{data.at("header").at("stamp").at("sec").get<std::int32_t>(),
                                 data.at("header").at("stamp").at("nanosec").get<std::uint32_t>()};
    const auto found = by_stamp.find(stamp.nanoseconds());
    if (found == by_stamp.end()) {
      continue;  // a handshake no-op
    }
    const CartesianCommand& command = found->second->command;
    EXPECT_EQ(data.at("fields").get<std::uint32_t>(), static_cast<std::uint32_t>(command.fields));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(data.at("position").at(k).get<double>(), command.position[k]);
    }
    EXPECT_EQ(data.at("orientation").at(3).get<double>(), command.orientation.w());
    ++matched;
  }
  EXPECT_EQ(matched, sent.size());
  // The outcomes say applied or stale, as the host decided.
  std::size_t stale = 0;
  for (const nlohmann::json& entry : node.at("messages").at(prefix + "/outcome")) {
    stale +=
        entry.at("data").at("reason").get<int>() == static_cast<int>(transport::Reason::kStaleStamp)
            ? 1
            : 0;
  }
  EXPECT_EQ(stale, sent.size() / 10);
  // Every cycle record carries the gains in force: the controller file's stiffness until the
  // cycle that took the command changing it, that command's from then on.
  const auto& changed = host_->outcomes().at(sent.at(kStiffnessChange).header.stamp.nanoseconds());
  ASSERT_EQ(changed.size(), 1U);
  ASSERT_EQ(changed[0].outcome, transport::Outcome::kApplied);
  const std::uint64_t changed_at = changed[0].cycle;
  const nlohmann::json& cycle_records = node.at("messages").at(prefix + "/cycle");
  ASSERT_EQ(cycle_records.size(), cycles);
  const nlohmann::json& initial =
      cycle_records.at(0).at("data").at("cartesian_in_force").at(0).at("stiffness_translational");
  EXPECT_GT(initial.at(0).get<double>(), 0.0);
  EXPECT_NE(initial.at(0).get<double>(), 2345.0);
  for (const nlohmann::json& entry : cycle_records) {
    const nlohmann::json& data = entry.at("data");
    ASSERT_EQ(data.at("cartesian_in_force").size(), 1U);
    ASSERT_EQ(data.at("joint_in_force").size(), 0U);
    const auto index = std::stoull(data.at("state").at("cycle").get<std::string>());
    const nlohmann::json& k = data.at("cartesian_in_force").at(0).at("stiffness_translational");
    ASSERT_EQ(k.at(0).get<double>(), index >= changed_at ? 2345.0 : initial.at(0).get<double>())
        << "cycle " << index << " (the change took effect at cycle " << changed_at << ")";
    ASSERT_EQ(k.at(8).get<double>(), index >= changed_at ? 1234.0 : initial.at(8).get<double>());
  }
}

TEST(LiveRecording, AHostKilledMidRecordingLeavesItsCompleteChunks) {
  const fs::path path = scratch("killed.mcap");
  const int domain = randomDomain();
  std::vector<std::string> args = hostArgs(domain, "rec_killed");
  args.insert(args.end(), {"--record", path.string()});
  Process host(args);
  Client client(domain, "rec_killed");
  // 2.5 s of cycles: the writer has written chunks (at most 0.5 s apart) when the host dies.
  ASSERT_TRUE(client.state(10s).has_value());
  std::this_thread::sleep_for(2500ms);
  host.signal(SIGKILL);
  host.wait(5s);

  const Channels channels = readRecording(path);
  EXPECT_FALSE(channels.contents.complete);
  EXPECT_GT(channels.contents.chunks, 0U);
  const std::uint64_t cycles = channels.counts.at("/rec_killed/cycle");
  EXPECT_GT(cycles, 1000U);
  for (std::uint64_t i = 0; i < cycles; ++i) {
    ASSERT_EQ(channels.cycles[i], i);  // the first cycles, whole and in order
  }
  const auto [inspect_code, inspect_text] = inspect(path);
  EXPECT_EQ(inspect_code, 1) << inspect_text;  // incomplete, but listed
  EXPECT_NE(inspect_text.find("INCOMPLETE"), std::string::npos) << inspect_text;
  EXPECT_NE(inspect_text.find(std::to_string(cycles)), std::string::npos) << inspect_text;
  if (!nodeAvailable()) {
    GTEST_SKIP() << "no node: the independent reader's check did not run";
  }
  const nlohmann::json node = readWithNode(path, 1);
  ASSERT_FALSE(node.is_null());
  EXPECT_TRUE(node.at("truncated").get<bool>());
  EXPECT_EQ(node.at("counts").at("/rec_killed/cycle").get<std::uint64_t>(), cycles);
}

// A file-size limit reached mid-run (as a full disk would be): the recording stops with the
// error named, the simulation runs to its end and succeeds, and what was written reads.
TEST(LiveRecording, AFullDiskStopsTheRecordingNotTheRun) {
  const fs::path path = scratch("limited.mcap");
  // ulimit -f counts 512-byte blocks in sh: 1 MiB, reached by the recording's second chunk.
  const std::string command = "ulimit -f 2048 && " + kComply + " sim --robot fr3 --config " +
                              kSourceDir + "/config/sim/cartesian_impedance.yaml --task " +
                              kSourceDir + "/examples/sim/press_on_table.yaml --no-plot --out '" +
                              scratch("limited_sim").string() + "' --record '" + path.string() +
                              "' 2>&1";
  const auto [status, text] = testing::runCommand("sh -c \"" + command + "\"");
  EXPECT_EQ(status, 0) << text;  // the run itself succeeded
  EXPECT_NE(text.find("recording stopped early"), std::string::npos) << text;
  EXPECT_NE(text.find("File too large"), std::string::npos) << text;
  EXPECT_LE(fs::file_size(path), 1024U * 1024U);
  // The log written beside it met the same limit, and the run says so.
  EXPECT_NE(text.find("log.csv is incomplete"), std::string::npos) << text;
  const record::McapContents contents = record::readMcap(path.string());
  EXPECT_FALSE(contents.complete);
  EXPECT_GT(contents.messages, 0U);
}

}  // namespace
}  // namespace comply::live_test
