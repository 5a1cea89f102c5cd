// The committed prefix asked over the wire (/<name>/committed_request, /<name>/committed), over DDS
// (`comply run` and its transport process) and in process alike: a policy that acts on a state
// asks what the host will execute from that state's stamp on while a chunk plays, and gets the
// chunk's reference at exactly the times it asked for; the states the host reports next carry the
// same reference at their times. A request the host cannot answer is refused naming the field.
// (The answer against the cycles to 1e-9 m, on a clock on the cycle's grid: live_committed_test.)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

using namespace std::chrono_literals;

constexpr double kDtS = 0.05;
constexpr std::uint32_t kCount = 16;

void sleepUntilWallClock(double seconds) {
  std::this_thread::sleep_until(std::chrono::system_clock::time_point(
      std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::duration<double>(seconds))));
}

transport::CommittedRequestMessage requestFrom(const transport::Stamp& observation, double dt_s,
                                               std::uint32_t count) {
  transport::CommittedRequestMessage request;
  request.header.stamp = transport::Stamp::now();
  request.observation = observation;
  request.dt_s = dt_s;
  request.count = count;
  return request;
}

/// The states the host reports until its stamp passes `until_s`, each once.
std::vector<transport::ControllerStateMessage> statesUntil(HostHarness& host, double until_s) {
  std::vector<transport::ControllerStateMessage> states;
  while (transport::Stamp::now().seconds() < until_s + 0.05) {
    const auto state = host.state(100ms);
    if (state && (states.empty() || state->header.stamp != states.back().header.stamp)) {
      states.push_back(*state);
    }
    std::this_thread::sleep_for(3ms);
  }
  return states;
}

TEST_P(LiveHostOn, AnswersTheCommittedPrefixOfAChunkOverTheWire) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("committed", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.connectChunks(1));

  // A 1.5 s chunk along y at 0.1 m/s that takes over at once.
  const double start_s = transport::Stamp::now().seconds() + 0.05;
  const transport::CartesianChunkMessage chunk = chunkOnLine(*state, start_s, start_s, 0.05, 30);
  ASSERT_TRUE(host.send(chunk, 1));
  const std::int64_t stamp = chunk.header.stamp.nanoseconds();
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return host.outcomes().count(stamp) > 0; }));
  ASSERT_EQ(host.outcomes()[stamp].front().outcome, transport::Outcome::kApplied)
      << host.outcomes()[stamp].front().message;

  // Past the blend onto it, a policy observes a state and asks from its stamp.
  sleepUntilWallClock(start_s + 0.2);
  const auto observed = host.state(2s);
  ASSERT_TRUE(observed);
  const transport::CommittedRequestMessage request =
      requestFrom(observed->header.stamp, kDtS, kCount);
  const std::int64_t asked_ns = transport::Stamp::now().nanoseconds();
  const auto answer = host.committed(request, 1, 5s);
  const std::int64_t answered_by_ns = transport::Stamp::now().nanoseconds();
  ASSERT_TRUE(answer) << "no answer to the committed request";
  ASSERT_TRUE(answer->answered) << answer->message;
  EXPECT_TRUE(answer->known);
  EXPECT_EQ(answer->message, "");
  EXPECT_EQ(answer->command_kind, transport::WireCommandKind::kCartesian);
  EXPECT_EQ(answer->header.frame_id, state->header.frame_id);
  EXPECT_GE(answer->header.stamp.nanoseconds(), asked_ns) << "answered on the host's clock";
  EXPECT_LE(answer->header.stamp.nanoseconds(), answered_by_ns);
  EXPECT_TRUE(answer->joint.empty());
  ASSERT_EQ(answer->cartesian.size(), kCount);

  // At exactly the times asked for, the chunk's line (up to where the host's clock stood between
  // its cycles when the chunk came and when the question did: 2 mm is 20 ms at 0.1 m/s), its x
  // and z as the chunk's, the gains in force.
  const std::int64_t observation_ns = request.observation.nanoseconds();
  for (std::uint32_t k = 0; k < kCount; ++k) {
    SCOPED_TRACE(k);
    const transport::CartesianCommandMessage& entry = answer->cartesian[k];
    EXPECT_EQ(entry.header.stamp.nanoseconds(), observation_ns + k * 50'000'000LL);
    const double t_s = entry.header.stamp.seconds();
    EXPECT_NEAR(entry.command.position.y(), state->tcp_position[1] + 0.1 * (t_s - start_s), 2e-3);
    EXPECT_NEAR(entry.command.position.x(), state->tcp_position[0], 1e-9);
    EXPECT_NEAR(entry.command.position.z(), state->tcp_position[2], 1e-9);
    EXPECT_GT(entry.command.stiffness_translational.trace(), 0.0);
  }

  // What the cycles then wrote: each state's reference at its stamp against the answer between
  // the two times around it (the line is straight between them). A state's stamp is taken after
  // its cycle, so it may run late on a busy machine: the median holds.
  const double first_s = answer->cartesian.front().header.stamp.seconds();
  const double last_s = answer->cartesian.back().header.stamp.seconds();
  std::vector<double> errors;
  for (const transport::ControllerStateMessage& s : statesUntil(host, last_s)) {
    const double at_s = s.header.stamp.seconds();
    if (at_s < first_s || at_s >= last_s) {
      continue;
    }
    const auto k = static_cast<std::size_t>((at_s - first_s) / kDtS);
    const double y0 = answer->cartesian[k].command.position.y();
    const double y1 = answer->cartesian[k + 1].command.position.y();
    const double y = y0 + (y1 - y0) * (at_s - first_s - kDtS * static_cast<double>(k)) / kDtS;
    errors.push_back(std::abs(s.reference_position[1] - y));
    EXPECT_NEAR(s.reference_position[0], answer->cartesian[k].command.position.x(), 1e-9);
  }
  ASSERT_GE(errors.size(), 20U) << "states over the answer's 0.75 s";
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 5e-4) << "the median state against the answer [m]";
}

TEST_P(LiveHostOn, RefusesACommittedRequestNamingTheField) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("committed_refused", 1);
  ASSERT_TRUE(state);
  const auto zero_dt = host.committed(requestFrom(state->header.stamp, 0.0, 4), 1, 5s);
  ASSERT_TRUE(zero_dt) << "a refusal is an answer too";
  EXPECT_FALSE(zero_dt->answered);
  EXPECT_FALSE(zero_dt->known);
  EXPECT_TRUE(zero_dt->cartesian.empty());
  EXPECT_EQ(zero_dt->message, "dt is 0: the step between the times [s] is finite and > 0");

  const auto too_many = host.committed(requestFrom(state->header.stamp, kDtS, 65), 1, 5s);
  ASSERT_TRUE(too_many);
  EXPECT_FALSE(too_many->answered);
  EXPECT_EQ(too_many->message, "count is 65: 1 to 64 times (a chunk's most waypoints)");

  // The host answers on: a good request after them is answered.
  const auto good = host.committed(requestFrom(state->header.stamp, kDtS, 64), 1, 5s);
  ASSERT_TRUE(good);
  EXPECT_TRUE(good->answered) << good->message;
  EXPECT_EQ(good->cartesian.size(), 64U);
}

/// `comply echo committed` prints every answer on the host's committed topic until `count`:
/// what it printed once a request from this process was answered (asked again every 100 ms
/// while the echo's reader and the host find each other).
std::string echoOfAnswer(ProcessHost& live, const std::string& name,
                         const transport::CommittedRequestMessage& request, bool json) {
  const std::string output = scratchFile(name + (json ? ".json" : ".txt"));
  std::vector<std::string> args = {"echo",   "committed", "--domain", std::to_string(live.domain),
                                   "--name", name,        "--count",  "1"};
  if (json) {
    args.emplace_back("--json");
  }
  Process echo(args, output);
  transport::Writer<transport::CommittedRequestMessage> writer(live.client.participant(), name);
  int code = -1;
  for (int attempt = 0; attempt < 200 && code < 0; ++attempt) {
    writer.write(request);
    code = echo.wait(100ms);
  }
  EXPECT_EQ(code, 0) << "comply echo committed printed no answer";
  std::ifstream printed(output);
  return {std::istreambuf_iterator<char>(printed), std::istreambuf_iterator<char>()};
}

TEST(LiveHost, EchoPrintsTheAnswersToCommittedRequests) {
  ProcessHost live("echo_committed");
  const auto state = live.client.state(20s);
  ASSERT_TRUE(state);
  const transport::CommittedRequestMessage request = requestFrom(state->header.stamp, kDtS, 3);
  const nlohmann::json answer =
      nlohmann::json::parse(echoOfAnswer(live, "echo_committed", request, true));
  EXPECT_EQ(answer["answered"], true) << answer.dump();
  EXPECT_EQ(answer["request_stamp"]["sec"], request.header.stamp.sec);
  EXPECT_EQ(answer["request_stamp"]["nanosec"], request.header.stamp.nanosec);
  EXPECT_EQ(answer["command_kind"], "cartesian");
  ASSERT_EQ(answer["cartesian"].size(), 3U) << answer.dump();
  EXPECT_EQ(answer["cartesian"][2]["header"]["stamp"]["nanosec"],
            (request.observation.nanoseconds() + 100'000'000) % 1'000'000'000);
  EXPECT_EQ(answer["cartesian"][0]["position"].size(), 3U);

  const std::string refused =
      echoOfAnswer(live, "echo_committed", requestFrom(state->header.stamp, kDtS, 0), false);
  EXPECT_NE(refused.find(" refused: count is 0: 1 to 64 times"), std::string::npos) << refused;
}

}  // namespace
}  // namespace comply::live_test
