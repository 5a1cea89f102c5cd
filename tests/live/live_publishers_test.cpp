// A live host against senders that die, compete or outlive it: the watchdog holds within the
// command timeout of a killed sender (`comply send`), a second publisher is refused until the first
// goes silent (on DDS and in process, live_harness.hpp), and a client carries on across a restart
// of `comply run` (SIGTERM: exit 0). And the state message the host builds from a cycle's sample
// carries the energy tank's account.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <thread>

#include "comply/host/controller_setup.hpp"
#include "comply/host/diagnostics_message.hpp"
#include "comply/host/state_sample.hpp"
#include "live_harness.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

constexpr double kCommandTimeoutS = 0.5;  // config/sim/cartesian_impedance.yaml

/// A JSON-lines stream for `comply send`: `count` poses wobbling 2 cm around the state's TCP.
std::string writeStream(const transport::ControllerStateMessage& state, int count,
                        const std::string& name) {
  const std::string file = scratchFile(name + ".jsonl");
  std::ofstream out(file);
  for (int i = 0; i < count; ++i) {
    const double y = state.tcp_position[1] + 0.02 * std::sin(2.0 * M_PI * i / 1000.0);
    out << "{\"position\": [" << state.tcp_position[0] << ", " << y << ", " << state.tcp_position[2]
        << "], \"orientation\": [" << state.tcp_orientation[0] << ", " << state.tcp_orientation[1]
        << ", " << state.tcp_orientation[2] << ", " << state.tcp_orientation[3] << "]}\n";
  }
  return file;
}

std::vector<std::string> senderArgs(int domain, const std::string& name, const std::string& file) {
  return {"send", "--domain", std::to_string(domain), "--name", name, "--file", file, "--rate",
          "1000", "--no-wait"};
}

TEST(LiveHost, WatchdogHoldsWithinTheTimeoutOfAKilledSender) {
  ProcessHost live("watchdog");
  const auto state = live.client.state(20s);
  ASSERT_TRUE(state);
  Process sender(senderArgs(live.domain, "watchdog", writeStream(*state, 20000, "watchdog")));
  ASSERT_TRUE(live.client.poll(20s, [](const auto& d) { return d.commands_applied >= 500; }));
  const std::uint64_t timeouts = live.client.last().watchdog_timeouts;
  sender.signal(SIGKILL);
  const auto killed = Clock::now();
  ASSERT_TRUE(live.client.poll(3s, [&](const auto& d) { return d.watchdog_timeouts > timeouts; }));
  // Fired within the 3 s poll, and not before the timeout: a lower bound on the wall clock holds
  // on any machine (a busy one only makes it later), an upper one would time the machine.
  const double after_s = std::chrono::duration<double>(Clock::now() - killed).count();
  EXPECT_GE(after_s, kCommandTimeoutS - 0.2) << "the watchdog fired before the timeout";
  std::printf("watchdog held %.3f s after the sender was killed (timeout %.1f s)\n", after_s,
              kCommandTimeoutS);
  // Holding: the reference stays where the last command left it.
  const auto first = live.client.state(1s);
  std::this_thread::sleep_for(200ms);
  const auto second = live.client.state(1s);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->reference_position, second->reference_position);
  EXPECT_EQ(second->state, transport::HostState::kActive);
}

/// A sender that exits cleanly releases the command topics at once: a second sender started right
/// after it used to be refused as other_publisher for the whole command_timeout_s.
TEST_P(LiveHostOn, APublisherThatLeavesReleasesTheCommandTopicsAtOnce) {
  HostHarness& host = *host_;
  // A publisher timeout (command_timeout_s) far longer than the test: a second publisher let in
  // at all was let in by the first's departure, not by its silence.
  host.setConfigFile(hostConfigWith("departure.yaml", "    command_timeout_s: 60.0\n"));
  // Publisher 1 takes the command topics, 2 is refused while 1 is there.
  const auto state = host.startConnected("departure", 2);
  ASSERT_TRUE(state);
  const transport::Stamp first_stamp = transport::Stamp::now();
  ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), first_stamp), 1));
  ASSERT_TRUE(host.poll(
      5s, [&](const auto&) { return host.outcomes().count(first_stamp.nanoseconds()) > 0; }));
  ASSERT_EQ(host.outcomes()[first_stamp.nanoseconds()].front().outcome,
            transport::Outcome::kApplied);

  host.close(1);
  const auto closed = Clock::now();
  std::optional<transport::CommandOutcomeMessage> applied;
  while (!applied && Clock::now() - closed < 5s) {
    std::this_thread::sleep_for(10ms);
    const transport::Stamp stamp = transport::Stamp::now();
    ASSERT_TRUE(host.send(poseCommand(*state, Eigen::Vector3d::Zero(), stamp), 2));
    host.poll(200ms, [&](const auto&) { return host.outcomes().count(stamp.nanoseconds()) > 0; });
    const auto& outcomes = host.outcomes()[stamp.nanoseconds()];
    if (!outcomes.empty() && outcomes.front().outcome == transport::Outcome::kApplied) {
      applied = outcomes.front();
    }
  }
  ASSERT_TRUE(applied) << "the second publisher was let in neither on the first's departure "
                          "nor within 5 s of it";
  std::printf("second publisher applied %.3f s after the first closed\n",
              std::chrono::duration<double>(Clock::now() - closed).count());
}

TEST_P(LiveHostOn, SecondPublisherIsRefusedUntilTheFirstGoesSilent) {
  HostHarness& host = *host_;
  // Both before either streams: the first's probe takes the command topics, the second's is
  // refused (an outcome all the same).
  const auto state = host.startConnected("lockout", 2);
  ASSERT_TRUE(state);

  // The first publisher: poses wobbling 2 cm along y at 1 kHz until it goes silent, as a sender
  // that dies would (the watchdog test kills a real one). A jthread: silenced and joined however
  // the test ends.
  std::atomic<int> first_refused_writes{0};
  std::jthread first([&](const std::stop_token& silent) {
    const auto begin = Clock::now();
    for (int i = 0; !silent.stop_requested(); ++i) {
      std::this_thread::sleep_until(begin + std::chrono::microseconds(1000 * i));
      const double y_m = 0.02 * std::sin(2.0 * M_PI * i / 1000.0);
      if (!host.send(poseCommand(*state, {0.0, y_m, 0.0}, transport::Stamp::now()), 1)) {
        ++first_refused_writes;
      }
    }
  });
  ASSERT_TRUE(host.poll(20s, [](const auto& d) { return d.commands_applied >= 200; }));

  std::map<std::int64_t, double> sent_after_silence_s;  // by stamp; negative: before the silence
  std::optional<Clock::time_point> silenced;
  const auto start = Clock::now();
  for (int i = 0; i < 100; ++i) {  // 2 s at 50 Hz; the first goes silent after 0.6 s
    std::this_thread::sleep_until(start + i * 20ms);
    if (i == 30) {
      first.request_stop();
      first.join();  // nothing from the first after this
      silenced = Clock::now();
    }
    const auto message = poseCommand(*state, Eigen::Vector3d::Zero(), transport::Stamp::now());
    ASSERT_TRUE(host.send(message, 2));
    sent_after_silence_s[message.header.stamp.nanoseconds()] =
        silenced ? std::chrono::duration<double>(Clock::now() - *silenced).count() : -1.0;
  }
  EXPECT_EQ(first_refused_writes.load(), 0);
  host.poll(5s, [&](const auto&) {
    return std::all_of(sent_after_silence_s.begin(), sent_after_silence_s.end(),
                       [&](const auto& sent) { return host.outcomes().count(sent.first) > 0; });
  });
  int refused = 0;
  int applied = 0;
  for (const auto& [stamp, after_s] : sent_after_silence_s) {
    ASSERT_EQ(host.outcomes()[stamp].size(), 1U) << "no (or two) outcomes for " << stamp;
    const auto& outcome = host.outcomes()[stamp].front();
    if (after_s < kCommandTimeoutS - 0.1) {  // the first publisher is alive or not yet silent
      EXPECT_EQ(outcome.reason, transport::Reason::kOtherPublisher) << after_s << " s";
      refused += outcome.reason == transport::Reason::kOtherPublisher ? 1 : 0;
    } else if (after_s > kCommandTimeoutS + 0.2) {  // silent long enough: the second takes over
      EXPECT_EQ(outcome.outcome, transport::Outcome::kApplied)
          << after_s << " s " << outcome.message;
      applied += outcome.outcome == transport::Outcome::kApplied ? 1 : 0;
    }
  }
  EXPECT_GE(refused, 30);
  EXPECT_GE(applied, 30);
}

/// The soak saw one sender given another's outcome: two senders' commands carried the same
/// stamp, and a client matched outcomes by stamp alone. An outcome names its sender.
TEST_P(LiveHostOn, TwoSendersOfOneStampEachGetTheirOwnOutcome) {
  HostHarness& host = *host_;
  const auto state = host.startConnected("same_stamp", 2);  // publisher 1 holds the topics
  ASSERT_TRUE(state);
  const transport::Gid holder = host.sender(1);
  const transport::Gid other = host.sender(2);
  ASSERT_NE(holder, other);
  ASSERT_NE(holder, transport::Gid{});

  const transport::Stamp stamp = transport::Stamp::now();
  ASSERT_TRUE(host.send(poseCommand(*state, {0.0, 0.01, 0.0}, stamp), 1));
  ASSERT_TRUE(host.send(poseCommand(*state, {0.0, -0.01, 0.0}, stamp), 2));
  ASSERT_TRUE(
      host.poll(5s, [&](const auto&) { return host.outcomes()[stamp.nanoseconds()].size() >= 2; }));
  const auto& outcomes = host.outcomes()[stamp.nanoseconds()];
  ASSERT_EQ(outcomes.size(), 2U);
  int checked = 0;
  for (const transport::CommandOutcomeMessage& outcome : outcomes) {
    if (outcome.sender == holder) {
      EXPECT_EQ(outcome.outcome, transport::Outcome::kApplied) << outcome.message;
      EXPECT_TRUE(transport::sentBy(outcome, holder));
      EXPECT_FALSE(transport::sentBy(outcome, other));
      ++checked;
    } else if (outcome.sender == other) {
      EXPECT_EQ(outcome.reason, transport::Reason::kOtherPublisher);
      EXPECT_TRUE(transport::sentBy(outcome, other));
      EXPECT_FALSE(transport::sentBy(outcome, holder));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2) << "an outcome named neither sender";
}

TEST(LiveHost, ClientCarriesOnAcrossAHostRestart) {
  const int domain = randomDomain();
  Client client(domain, "restart");
  transport::Writer<transport::CartesianCommandMessage> writer(client.participant(), "restart");
  const auto sendTen = [&](const transport::ControllerStateMessage& state) {
    std::vector<std::int64_t> stamps;
    for (int i = 0; i < 10; ++i) {
      const auto message = poseCommand(state, Eigen::Vector3d::Zero(), transport::Stamp::now());
      EXPECT_TRUE(writer.write(message));
      stamps.push_back(message.header.stamp.nanoseconds());
      std::this_thread::sleep_for(10ms);
    }
    return stamps;
  };
  const auto allApplied = [&](const std::vector<std::int64_t>& stamps) {
    return client.poll(5s, [&](const auto&) {
      return std::all_of(stamps.begin(), stamps.end(), [&](std::int64_t stamp) {
        const auto& outcomes = client.outcomes()[stamp];
        return outcomes.size() == 1 && outcomes[0].outcome == transport::Outcome::kApplied;
      });
    });
  };
  {
    Process host(hostArgs(domain, "restart"));
    const auto state = client.state(20s);
    ASSERT_TRUE(state);
    ASSERT_TRUE(writer.waitForMatch(1, 10.0));
    ASSERT_TRUE(handshake(writer, client, 7));
    EXPECT_TRUE(allApplied(sendTen(*state)));
    host.signal(SIGTERM);
    EXPECT_EQ(host.wait(10s), 0) << "comply run did not exit 0 on SIGTERM";
  }
  Process host(hostArgs(domain, "restart"));
  client.state(100ms);  // drop the old host's last states
  const auto state = client.state(20s);
  ASSERT_TRUE(state);
  ASSERT_TRUE(writer.waitForMatch(1, 10.0));
  ASSERT_TRUE(handshake(writer, client, 7)) << "the same writer does not reach the new host";
  EXPECT_TRUE(allApplied(sendTen(*state)));
}

TEST(LiveHost, APositionAloneFromCommandSendKeepsTheOrientationInForce) {
  // The wire carries the pose as one group: `comply send` completes a position given alone with
  // the orientation in force (from the host's state), as the Python client does, instead of
  // sending the group's identity orientation (a 180 degree pose_jump on the FR3).
  ProcessHost live("partial");
  const auto before = live.client.state(20s);
  ASSERT_TRUE(before);
  std::ostringstream json;
  json << "{\"position\": [" << before->reference_position[0] << ", "
       << before->reference_position[1] + 0.01 << ", " << before->reference_position[2] << "]}";
  Process sender(
      {"send", "--domain", std::to_string(live.domain), "--name", "partial", "--json", json.str()});
  EXPECT_EQ(sender.wait(20s), 0) << "the command was not applied";
  std::optional<transport::ControllerStateMessage> after;
  for (int attempt = 0; attempt < 50; ++attempt) {
    after = live.client.state(1s);
    if (after && after->reference_position[1] > before->reference_position[1] + 0.005) {
      break;
    }
  }
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->reference_position[1], before->reference_position[1] + 0.01, 1e-9);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(after->reference_orientation[i], before->reference_orientation[i], 1e-9) << i;
  }
}

/// `comply send --file` with 300 commands at 100 Hz used to report "192 of 300 commands without an
/// outcome" (exit 1) when all were applied: it read the outcomes only after sending, from a
/// keep-last reader. And at a high --rate its keep-last writer dropped commands before they left.
TEST(LiveHost, CommandSendAccountsEveryCommandOfAFileAtAnyRate) {
  ProcessHost live("file");
  const auto state = live.client.state(20s);
  ASSERT_TRUE(state);
  const std::string file = scratchFile("send.jsonl");
  {
    std::ofstream lines(file);
    for (int i = 0; i < 300; ++i) {
      lines << "{\"position\": [" << state->reference_position[0] << ", "
            << state->reference_position[1] + 0.005 * std::sin(0.05 * i) << ", "
            << state->reference_position[2] << "]}\n";
    }
  }
  for (const std::string rate : {"100", "5000"}) {
    SCOPED_TRACE("--rate " + rate);
    const SendResult sent = sendFile(live.domain, "file", file, rate);
    EXPECT_EQ(sent.exit_code, sent.rejected == 0 ? 0 : 1) << "1: some refused, as documented";
    EXPECT_EQ(sent.text.find("without an outcome"), std::string::npos)
        << sent.text.substr(sent.text.size() > 300 ? sent.text.size() - 300 : 0);
    // Every command has its outcome. At 100 Hz the host takes each; at 5 kHz, five commands a
    // cycle, a loaded machine's host may fall behind, and queue_full is then the right answer.
    EXPECT_EQ(sent.applied + sent.rejected, 300U) << sent.text.substr(0, 2000);
    EXPECT_EQ(sent.rejected, sent.queue_full) << sent.text.substr(0, 2000);
    if (rate == "100") {
      EXPECT_EQ(sent.applied, 300U) << sent.text.substr(0, 2000);
    } else {
      EXPECT_GE(sent.applied, 150U) << sent.text.substr(0, 2000);
    }
  }
  std::filesystem::remove(file);
}

/// The FR3 under config/sim's Cartesian controller, as comply sim resolves it.
std::shared_ptr<const pipeline::ResolvedController> simFr3Controller() {
  return pipeline::resolveController(host::simControllerConfig(
      "fr3", "",
      (std::filesystem::path(COMPLY_SOURCE_DIR) / "config" / "sim" / "cartesian_impedance.yaml")
          .string()));
}

/// A state sample of `dof` joints at zero, commanding no torque.
host::StateSample restingSample(int dof) {
  host::StateSample sample;
  sample.joints = JointState::zero(dof);
  sample.torque.setZero(dof);
  return sample;
}

TEST(LiveState, CarriesTheTanksAccount) {
  const auto resolved = simFr3Controller();
  host::StateSample sample = restingSample(resolved->dof);
  // Every field away from its default, each value distinct, so a swap shows.
  sample.passivity = {.enabled = true,
                      .tank_energy_j = 0.75,
                      .nullspace_tank_energy_j = 0.25,
                      .injected_j = 1.5,
                      .dissipated_j = 2.125,
                      .refused_j = 0.0625,
                      .gain_fraction = 0.4};
  const transport::ControllerStateMessage message = host::stateMessage(sample, *resolved);
  EXPECT_TRUE(message.passivity);
  EXPECT_EQ(message.tank_energy_j, 0.75);
  EXPECT_EQ(message.nullspace_tank_energy_j, 0.25);
  EXPECT_EQ(message.energy_injected_j, 1.5);
  EXPECT_EQ(message.energy_dissipated_j, 2.125);
  EXPECT_EQ(message.energy_refused_j, 0.0625);
  EXPECT_EQ(message.gain_fraction, 0.4);
  EXPECT_FALSE(message.walls);
}

TEST(LiveState, CarriesTheWallsDistanceAndBarrierForce) {
  const auto resolved = simFr3Controller();
  host::StateSample sample = restingSample(resolved->dof);
  sample.walls = true;
  sample.wall_distance_m = -0.0025;
  sample.wall_force = Eigen::Vector3d(-12.5, 0.5, 3.0);
  sample.workspace_min = Eigen::Vector3d(0.25, -0.5, 0.125);
  sample.workspace_max = Eigen::Vector3d(0.75, 0.5, 0.875);
  const transport::ControllerStateMessage message = host::stateMessage(sample, *resolved);
  EXPECT_TRUE(message.walls);
  EXPECT_EQ(message.wall_distance_m, -0.0025);
  EXPECT_EQ(message.wall_force[0], -12.5);
  EXPECT_EQ(message.wall_force[1], 0.5);
  EXPECT_EQ(message.wall_force[2], 3.0);
  EXPECT_EQ(message.workspace_min[0], 0.25);
  EXPECT_EQ(message.workspace_min[2], 0.125);
  EXPECT_EQ(message.workspace_max[1], 0.5);
  EXPECT_EQ(message.workspace_max[2], 0.875);
}

TEST(LiveState, CarriesTheReflexsThresholdsAndItsTrip) {
  const auto resolved = simFr3Controller();
  host::StateSample sample = restingSample(resolved->dof);
  EXPECT_FALSE(host::stateMessage(sample, *resolved).reflex_tripped);
  sample.reflex = true;
  sample.reflex_force_threshold = Eigen::Vector3d(20.0, 20.0, 45.0);
  sample.reflex_torque_threshold = Eigen::Vector3d(5.0, 5.0, 2.5);
  sample.reflex_tripped = true;
  sample.reflex_reaction = transport::ReflexReaction::kRetreat;
  sample.reflex_wrench << 0.5, 30.25, -1.0, 0.125, 0.0, -0.25;
  const transport::ControllerStateMessage message = host::stateMessage(sample, *resolved);
  EXPECT_TRUE(message.reflex);
  EXPECT_EQ(message.reflex_force_threshold[2], 45.0);
  EXPECT_EQ(message.reflex_torque_threshold[2], 2.5);
  EXPECT_TRUE(message.reflex_tripped);
  EXPECT_EQ(message.reflex_reaction, transport::ReflexReaction::kRetreat);
  EXPECT_EQ(message.reflex_wrench[1], 30.25);
  EXPECT_EQ(message.reflex_wrench[5], -0.25);
  EXPECT_EQ(transport::toString(message.reflex_reaction), "retreat");
}

TEST(LiveState, CarriesTheContactSpeedLimitShareAndBraking) {
  const auto resolved = simFr3Controller();
  host::StateSample sample = restingSample(resolved->dof);
  EXPECT_EQ(host::stateMessage(sample, *resolved).contact_speed_share, 1.0) << "off: all of it";
  sample.contact_speed_limit_m_per_s = 0.2625;
  sample.contact_speed_share = 0.375;
  sample.contact_speed_brake_n = 4.5;
  const transport::ControllerStateMessage message = host::stateMessage(sample, *resolved);
  EXPECT_EQ(message.contact_speed_limit_m_per_s, 0.2625);
  EXPECT_EQ(message.contact_speed_share, 0.375);
  EXPECT_EQ(message.contact_speed_brake_n, 4.5);
}

// The state's frame is the model's: a controller file may name a base other than robot.yaml's
// (here the UR5e's base_link_inertia, turned half a turn about z from base_link).
TEST(LiveState, IsInTheControllerFilesBaseFrame) {
  pipeline::WrapperConfig config = host::simControllerConfig(
      "ur5e", "",
      (std::filesystem::path(COMPLY_SOURCE_DIR) / "config" / "sim" / "cartesian_impedance.yaml")
          .string());
  config.base_frame = "base_link_inertia";
  const auto resolved = pipeline::resolveController(config);
  ASSERT_NE(resolved->robot.base_frame, config.base_frame);
  host::StateSample sample;
  sample.joints = JointState::zero(resolved->dof);
  sample.torque.setZero(resolved->dof);
  EXPECT_EQ(host::stateMessage(sample, *resolved).header.frame_id, "base_link_inertia");
}

}  // namespace
}  // namespace comply::live_test
