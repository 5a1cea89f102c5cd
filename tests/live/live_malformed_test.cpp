// comply run under a peer that floods samples CycloneDDS cannot read. CycloneDDS logs a warning per
// such sample, and the host once printed every one (125,000 lines in one run of a flood). Now the
// first few are printed, then at most one count a second, and the total comes with the run's
// summary: every malformed sample is accounted for, in a few lines.

#include <dds/dds.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "comply_msgs/msg/Request.h"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

constexpr int kSamples = 2000;
constexpr int kPrintedSamples = 5;  // the lines printed before the counting starts

/// Writes Request_ samples on the host's Cartesian command topic, under the Cartesian command's
/// type name and without type information: the host matches the writer by name, and CycloneDDS
/// cannot deserialise a single sample (a Request_ is far shorter than a CartesianCommand_).
class MalformedWriter {
 public:
  MalformedWriter(transport::Participant& participant, const std::string& name) {
    const dds_topic_descriptor_t& request = comply_msgs_msg_dds__Request__desc;
    static const dds_topic_descriptor_t kDescriptor{request.m_size,
                                                    request.m_align,
                                                    request.m_flagset & ~DDS_TOPIC_XTYPES_METADATA,
                                                    request.m_nkeys,
                                                    "comply_msgs::msg::dds_::CartesianCommand_",
                                                    request.m_keys,
                                                    request.m_nops,
                                                    request.m_ops,
                                                    request.m_meta,
                                                    {nullptr, 0},
                                                    {nullptr, 0},
                                                    0};
    const std::string topic_name = transport::topicName(name, transport::Topic::kCartesianCommand);
    topic_ =
        dds_create_topic(participant.handle(), &kDescriptor, topic_name.c_str(), nullptr, nullptr);
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
    writer_ = dds_create_writer(participant.handle(), topic_, qos, nullptr);
    dds_delete_qos(qos);
  }
  ~MalformedWriter() {
    dds_delete(writer_);
    dds_delete(topic_);
  }
  MalformedWriter(const MalformedWriter&) = delete;
  MalformedWriter& operator=(const MalformedWriter&) = delete;

  [[nodiscard]] bool valid() const { return topic_ > 0 && writer_ > 0; }
  bool waitForMatch(std::chrono::milliseconds timeout) const {
    const auto deadline = Clock::now() + timeout;
    dds_publication_matched_status_t status{};
    while (dds_get_publication_matched_status(writer_, &status) >= 0 && status.current_count == 0 &&
           Clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);
    }
    return status.current_count > 0;
  }
  bool write() {
    comply_msgs_msg_dds__Request_ sample{};
    sample.header.frame_id = const_cast<char*>("");
    return dds_write(writer_, &sample) >= 0;
  }
  /// Until every sample written was acknowledged by the host.
  bool flush(std::chrono::seconds timeout) {
    return dds_wait_for_acks(writer_, DDS_SECS(timeout.count())) >= 0;
  }

 private:
  dds_entity_t topic_ = 0;
  dds_entity_t writer_ = 0;
};

std::vector<std::string> linesOf(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

TEST(LiveMalformed, AFloodOfUnreadableSamplesIsCountedNotPrintedOneByOne) {
  const int domain = randomDomain();
  const std::string name = "malformed";
  const std::string output = scratchFile("malformed.log");
  Process host(hostArgs(domain, name), output);
  Client client(domain, name);
  ASSERT_TRUE(client.state(20s)) << "no state from comply run";
  MalformedWriter writer(client.participant(), name);
  ASSERT_TRUE(writer.valid());
  ASSERT_TRUE(writer.waitForMatch(10s)) << "the host did not match the foreign writer";
  const auto start = Clock::now();
  for (int i = 0; i < kSamples; ++i) {
    ASSERT_TRUE(writer.write());
  }
  ASSERT_TRUE(writer.flush(10s)) << "the host did not acknowledge every sample";
  std::this_thread::sleep_for(1500ms);  // a window closes: a count is printed while the host runs
  host.signal(SIGTERM);
  ASSERT_EQ(host.wait(10s), 0) << "comply run did not exit 0 on SIGTERM";
  const double run_s = std::chrono::duration<double>(Clock::now() - start).count();

  int printed = 0;
  int counts = 0;
  long counted = 0;
  std::string summary;
  const std::regex count_line(R"(^DDS: (\d+) more malformed samples? in the last \d+\.\d s, )"
                              R"(not printed one by one$)");
  for (const std::string& line : linesOf(output)) {
    std::smatch match;
    if (line.find("deserialization") != std::string::npos) {
      ++printed;
    } else if (std::regex_match(line, match, count_line)) {
      ++counts;
      counted += std::stol(match[1]);
    } else if (line.find("malformed samples dropped by the transport") != std::string::npos) {
      summary = line;
    }
  }
  std::filesystem::remove(output);
  EXPECT_EQ(printed, kPrintedSamples) << "one line per malformed sample is a flood of its own";
  EXPECT_GE(counts, 1);
  EXPECT_LE(counts, static_cast<int>(run_s) + 2) << "at most one count a second, and the rest";
  EXPECT_EQ(printed + counted, kSamples) << "every malformed sample is printed or counted";
  EXPECT_NE(
      summary.find("; malformed samples dropped by the transport " + std::to_string(kSamples)),
      std::string::npos)
      << summary;
}

}  // namespace
}  // namespace comply::live_test
