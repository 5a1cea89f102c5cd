// Requests have outcomes as commands do: `comply send --request` reports what the host made of its
// request and exits 1 on a refusal, and the in-process host settles every request, a refused one
// with its reason.

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <iterator>
#include <optional>
#include <thread>

#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

/// `comply send --request <request>` to host `name`: its exit code and what it printed.
std::pair<int, std::string> sendRequest(int domain, const std::string& name,
                                        const std::string& request) {
  const std::string output = scratchFile(name + "." + request + ".out");
  Process sender({"send", "--domain", std::to_string(domain), "--name", name, "--request", request},
                 output);
  const int code = sender.wait(60s);
  std::ifstream printed(output);
  return {code,
          std::string((std::istreambuf_iterator<char>(printed)), std::istreambuf_iterator<char>())};
}

/// A deactivate from another process than the one commanding the arm used to print "sent request
/// deactivate" and exit 0, although the host refused it. It is reported refused, with the reason.
TEST(LiveHost, CommandSendReportsARefusedRequestAndExitsOne) {
  ProcessHost live("requests");
  const auto state = live.client.state(20s);
  ASSERT_TRUE(state);
  std::optional<transport::Writer<transport::CartesianCommandMessage>> writer;
  writer.emplace(live.client.participant(), "requests");
  ASSERT_TRUE(writer->waitForMatch(1, 10.0));
  ASSERT_TRUE(handshake(*writer, live.client, 7));
  // This process holds the command topics while `comply send` asks: it keeps commanding (the
  // publisher rule lets another process in once the holder is silent for command_timeout_s).
  std::atomic<bool> commanding{true};
  std::jthread holder([&] {
    while (commanding.load()) {
      writer->write(poseCommand(*state, Eigen::Vector3d::Zero(), transport::Stamp::now()));
      std::this_thread::sleep_for(20ms);
    }
  });
  const auto [refused_code, refused_text] = sendRequest(live.domain, "requests", "deactivate");
  EXPECT_EQ(refused_code, 1) << refused_text;
  EXPECT_NE(refused_text.find("request refused"), std::string::npos) << refused_text;
  EXPECT_NE(refused_text.find("other_publisher"), std::string::npos) << refused_text;
  const auto after = live.client.state(1s);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->state, transport::HostState::kActive) << "another process deactivated the arm";

  // The holder's writer gone, the topics are free: the same request is carried out.
  commanding = false;
  holder.join();
  writer.reset();
  ASSERT_TRUE(live.client.poll(20s, [](const auto& d) { return d.publisher.empty(); }));
  const auto [code, text] = sendRequest(live.domain, "requests", "deactivate");
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("request carried out"), std::string::npos) << text;
  std::optional<transport::ControllerStateMessage> now;
  const auto deadline = Clock::now() + 20s;
  while (Clock::now() < deadline && (!now || now->state != transport::HostState::kInactive)) {
    now = live.client.state(100ms);
  }
  ASSERT_TRUE(now);
  EXPECT_EQ(now->state, transport::HostState::kInactive);
}

/// The outcomes of kind request among those seen, by stamp.
std::vector<transport::CommandOutcomeMessage> requestOutcomes(HostHarness& host) {
  std::vector<transport::CommandOutcomeMessage> found;
  for (const auto& [stamp, outcomes] : host.outcomes()) {
    for (const transport::CommandOutcomeMessage& outcome : outcomes) {
      if (outcome.command_kind == transport::WireCommandKind::kRequest) {
        found.push_back(outcome);
      }
    }
  }
  return found;
}

/// Every request is settled: another process's refused as other_publisher, a probe answered
/// without taking the command topics, the holder's own carried out; none counted as a command.
TEST_F(LiveHostInProcess, EveryRequestHasAnOutcome) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("request_outcomes", 1);  // publisher 1 holds the topics
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), transport::Stamp::now()), 1));
  ASSERT_TRUE(host.poll(5s, [](const auto& d) { return d.commands_applied > 0; }));
  const std::uint64_t received = host.last().commands_received;
  host.outcomes().clear();

  ASSERT_TRUE(host.request(transport::RequestType::kDeactivate, 2));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return requestOutcomes(host).size() == 1; }));
  const transport::CommandOutcomeMessage refused = requestOutcomes(host).front();
  EXPECT_EQ(refused.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(refused.reason, transport::Reason::kOtherPublisher);
  EXPECT_EQ(refused.sender, host.sender(2));
  EXPECT_NE(refused.message.find("request refused"), std::string::npos) << refused.message;

  host.outcomes().clear();
  ASSERT_TRUE(host.request(transport::RequestType::kProbe, 3));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return requestOutcomes(host).size() == 1; }));
  EXPECT_EQ(requestOutcomes(host).front().outcome, transport::Outcome::kApplied)
      << "a probe is answered whoever holds the topics";
  EXPECT_EQ(requestOutcomes(host).front().sender, host.sender(3));

  host.outcomes().clear();
  ASSERT_TRUE(host.request(transport::RequestType::kDeactivate, 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return requestOutcomes(host).size() == 1; }));
  const transport::CommandOutcomeMessage carried_out = requestOutcomes(host).front();
  EXPECT_EQ(carried_out.outcome, transport::Outcome::kApplied) << carried_out.message;
  EXPECT_EQ(carried_out.reason, transport::Reason::kNone);
  EXPECT_EQ(host.last().commands_received, received) << "a request counted as a command";
}

/// A request is reported carried out once it was: the diagnostics that bring a deactivate's or
/// an activate's outcome already show the state it led to (they were reported at once, before
/// the control thread acted, and two in one batch left one undone). A reset with no fault to
/// leave is carried out too (it clears the stamp floor).
TEST_F(LiveHostInProcess, ARequestIsReportedCarriedOutOnceItWas) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("carried_out", 1);
  ASSERT_TRUE(state);
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), transport::Stamp::now()), 1));
  ASSERT_TRUE(host.poll(5s, [](const auto& d) { return d.commands_applied > 0; }));
  const auto stateWithOutcome = [&](transport::RequestType request) {
    host.outcomes().clear();
    EXPECT_TRUE(host.request(request, 1));
    std::optional<transport::HostState> seen;
    EXPECT_TRUE(host.poll(5s, [&](const transport::DiagnosticsMessage& d) {
      const auto found = requestOutcomes(host);
      if (found.empty()) {
        return false;
      }
      EXPECT_EQ(found.front().outcome, transport::Outcome::kApplied) << found.front().message;
      seen = d.state;
      return true;
    }));
    return seen;
  };
  for (int round = 0; round < 5; ++round) {
    SCOPED_TRACE(round);
    EXPECT_EQ(stateWithOutcome(transport::RequestType::kDeactivate),
              transport::HostState::kInactive);
    EXPECT_EQ(stateWithOutcome(transport::RequestType::kActivate), transport::HostState::kActive);
  }
  EXPECT_EQ(stateWithOutcome(transport::RequestType::kReset), transport::HostState::kActive);
}

/// A request the host cannot read in full still names its stamp and sender: it is answered,
/// refused for what it held (a frame_id over its bound; a nanosec out of range, under the stamp
/// as sent), and changes nothing.
TEST_F(LiveHostInProcess, AMalformedRequestIsAnsweredWithItsReason) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("malformed_request", 1);
  ASSERT_TRUE(state);
  host.outcomes().clear();
  transport::RequestMessage large;
  large.header.stamp = transport::Stamp::now();
  large.header.frame_id = std::string(4096, 'x');
  large.request = transport::RequestType::kDeactivate;
  ASSERT_TRUE(host.send(large, 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return requestOutcomes(host).size() == 1; }));
  const transport::CommandOutcomeMessage too_large = requestOutcomes(host).front();
  EXPECT_EQ(too_large.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(toString(too_large.reason), "too_large") << too_large.message;
  EXPECT_EQ(too_large.stamp, large.header.stamp);

  host.outcomes().clear();
  transport::RequestMessage odd;
  odd.header.stamp = {static_cast<std::int32_t>(transport::Stamp::now().sec), 1'500'000'000U};
  odd.request = transport::RequestType::kDeactivate;
  ASSERT_TRUE(host.send(odd, 1));
  ASSERT_TRUE(host.poll(5s, [&](const auto&) { return requestOutcomes(host).size() == 1; }));
  const transport::CommandOutcomeMessage invalid = requestOutcomes(host).front();
  EXPECT_EQ(invalid.outcome, transport::Outcome::kRejected);
  EXPECT_EQ(toString(invalid.reason), "invalid_stamp") << invalid.message;
  EXPECT_EQ(invalid.stamp.sec, odd.header.stamp.sec);
  EXPECT_EQ(invalid.stamp.nanosec, odd.header.stamp.nanosec) << "not the stamp as sent";
  EXPECT_EQ(host.last().state, transport::HostState::kActive) << "a refused request was done";
}

}  // namespace
}  // namespace comply::live_test
