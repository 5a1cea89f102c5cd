// The limit on CycloneDDS's per-sample warnings (src/transport/malformed_log.hpp): the first few
// lines of a flood as they come, then at most one count a window, every event accounted for. And
// the sink itself, fed through CycloneDDS's own log call.

#include "../../src/transport/malformed_log.hpp"

#include <dds/dds.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace comply::transport {
namespace {

constexpr std::int64_t kSecondNs = 1'000'000'000;

TEST(EventRateLimit, PrintsTheFirstEventsThenCountsAtMostOnceAWindow) {
  EventRateLimit limit(3, kSecondNs);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(limit.admit(i));
  }
  // 1000 events a second for 2.5 s after the first three.
  std::uint64_t reported = 0;
  int reports = 0;
  std::int64_t last_report_ns = -kSecondNs;
  for (std::int64_t t = 1'000'000; t <= 2'500'000'000; t += 1'000'000) {
    EXPECT_FALSE(limit.admit(t));
    const EventRateLimit::Report report = limit.take(t);
    if (report.count > 0) {
      EXPECT_GE(t - last_report_ns, kSecondNs) << "two counts within a window";
      EXPECT_EQ(report.span_ns, kSecondNs);
      last_report_ns = t;
      reported += report.count;
      ++reports;
    }
  }
  EXPECT_EQ(reports, 2);  // at 1.001 s and 2.002 s
  EXPECT_EQ(limit.take(2'600'000'000).count, 0U) << "the rest is owed until its window closes";
  const EventRateLimit::Report rest = limit.take(2'600'000'000, true);
  EXPECT_EQ(3 + reported + rest.count, 3U + 2500U);
  EXPECT_EQ(limit.total(), 3U + 2500U);
  EXPECT_EQ(limit.take(10 * kSecondNs, true).count, 0U) << "nothing is reported twice";
}

TEST(MalformedSampleLog, RecognisesCycloneDdsLinesAboutUnreadableSamples) {
  EXPECT_TRUE(isMalformedSampleLine(
      "data(application, vendor 1.16): 11098d0:c047be19:c35c81a5:103 #1: deserialization "
      "rt/x/cartesian_command/comply_msgs::msg::dds_::CartesianCommand_ failed (for reasons "
      "unknown)"));
  EXPECT_TRUE(isMalformedSampleLine("malformed packet received from vendor 1.16 state parse:data"));
  EXPECT_FALSE(isMalformedSampleLine("config: //CycloneDDS/Domain: unknown element"));
}

// Through dds_log, as CycloneDDS's receive thread writes its warnings (DDS_WARNING is C only).
TEST(MalformedSampleLog, AFloodOfWarningsBecomesAFewLinesAndATotal) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    MalformedSampleLog log(out);
    for (int i = 0; i < 1000; ++i) {
      dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "test",
              "data(application, vendor 1.16): 1:2:3:4 #%d: deserialization t/T failed\n", i);
    }
    dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "test", "another warning, passed as it comes\n");
    EXPECT_EQ(log.total(), 1000U);
  }
  std::rewind(out);
  int deserialization = 0;
  int counts = 0;
  unsigned long long counted = 0;
  bool other = false;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, out) != nullptr) {
    const std::string line = buffer;
    unsigned long long count = 0;
    if (line.find("deserialization") != std::string::npos) {
      ++deserialization;
    } else if (std::sscanf(buffer, "DDS: %llu more malformed sample", &count) == 1) {
      ++counts;
      counted += count;
    } else if (line.find("another warning, passed as it comes") != std::string::npos) {
      other = true;
    }
  }
  std::fclose(out);
  EXPECT_EQ(deserialization, static_cast<int>(MalformedSampleLog::kPrintedSamples));
  EXPECT_EQ(counts, 1) << "the rest, at the end (the flood lasted less than a window)";
  EXPECT_EQ(counted, 1000U - MalformedSampleLog::kPrintedSamples);
  EXPECT_TRUE(other);
}

}  // namespace
}  // namespace comply::transport
