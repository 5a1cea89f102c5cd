// comply run for a user who may not have real-time scheduling (no root, no CAP_SYS_NICE, an rtprio
// limit of 0: every user but root on a stock Linux). The host and its transport process used to
// ask CycloneDDS for SCHED_FIFO receive threads regardless; CycloneDDS could not start them and
// aborted the transport process, and the host exited 2. Now both run at normal priority, the
// host with one warning that says what it loses and how to grant it.
//
// The right is dropped for the child alone, so the tests run alike as root (CI) and as a user:
// an rtprio limit of 0, and no CAP_SYS_NICE to start from (off the bounding set, which is what
// root's programs get their capabilities from, and off the ambient set).

#include <gtest/gtest.h>
#include <linux/capability.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>

#include <array>
#include <cstdint>

#include "frames.hpp"
#include "live_support.hpp"
#include "realtime_grant.hpp"
#include "text_file.hpp"

namespace comply::live_test {
namespace {

using testing::textOf;

const std::string kTransportProgram = COMPLY_TRANSPORT_PROGRAM;

/// Between fork and exec (system calls only): what the child starts has no right to real-time
/// scheduling.
void dropRealtimeRights() {
  const rlimit none{0, 0};
  setrlimit(RLIMIT_RTPRIO, &none);
  prctl(PR_CAP_AMBIENT, PR_CAP_AMBIENT_CLEAR_ALL, 0, 0, 0);
  prctl(PR_CAPBSET_DROP, CAP_SYS_NICE, 0, 0, 0);
}

/// Whether dropRealtimeRights() takes the right away here: a user has it only by an rtprio limit
/// or a capability it may give up; root needs CAP_SETPCAP to narrow its bounding set.
bool canDropRealtimeRights() {
  return geteuid() != 0 || host::hasEffectiveCapability(CAP_SETPCAP);
}

/// The lines of `text` that hold `word`.
std::vector<std::string> linesWith(const std::string& text, const std::string& word) {
  std::vector<std::string> found;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(word) != std::string::npos) {
      found.push_back(line);
    }
  }
  return found;
}

TEST(LiveUnprivileged, AHostWithoutRealTimeRightsRunsAtNormalPriorityAndSaysSoOnce) {
  if (!canDropRealtimeRights()) {
    GTEST_SKIP() << "root without CAP_SETPCAP cannot give up CAP_SYS_NICE for a child";
  }
  const int domain = randomDomain();
  const std::string log = scratchFile("unprivileged_host.log");
  Client client(domain, "unprivileged");
  transport::Writer<transport::CartesianCommandMessage> writer(client.participant(),
                                                               "unprivileged");
  // As the README starts it: --sim at the default --priority 80.
  Process host(hostArgs(domain, "unprivileged"), log, dropRealtimeRights);
  const auto state = client.state(20s);
  ASSERT_TRUE(state) << "the host never published a state:\n" << textOf(log);
  ASSERT_TRUE(writer.waitForMatch(1, 10.0));
  ASSERT_TRUE(handshake(writer, client, 7));
  const auto command = poseCommand(*state, {0.0, 0.01, 0.0}, transport::Stamp::now());
  ASSERT_TRUE(writer.write(command));
  const std::int64_t stamp = command.header.stamp.nanoseconds();
  EXPECT_TRUE(client.poll(5s, [&](const auto&) {
    const auto& outcomes = client.outcomes()[stamp];
    return outcomes.size() == 1 && outcomes[0].outcome == transport::Outcome::kApplied;
  })) << "the command was not applied";
  host.signal(SIGTERM);
  EXPECT_EQ(host.wait(10s), 0) << textOf(log);

  const std::string text = textOf(log);
  const std::vector<std::string> warnings = linesWith(text, "warning");
  ASSERT_EQ(warnings.size(), 1U) << text;
  for (const char* said : {"comply run: warning: no real-time scheduling", "SCHED_FIFO priority 80",
                           "normal priority", "rtprio", "CAP_SYS_NICE"}) {
    EXPECT_NE(warnings[0].find(said), std::string::npos) << said << " in\n" << warnings[0];
  }
  EXPECT_EQ(text.find("pthread_create"), std::string::npos) << text;
  EXPECT_EQ(linesWith(text, " cycles, ").size(), 1U) << "no summary:\n" << text;
}

/// A user whose rtprio limit is below the asked priority gets real-time scheduling up to the
/// limit (before, it got none); one without a limit, or refused even at it, gets none. (The
/// sandbox CI runs in cannot raise its own limit, so this is the decision alone.)
TEST(LiveUnprivileged, AnRtprioLimitBelowTheAskedPriorityIsWhatTheHostRunsAt) {
  const auto upTo = [](int limit) { return [limit](int p) { return p <= limit; }; };
  EXPECT_EQ(host::grantablePriority(80, 99, upTo(99)), 80);
  EXPECT_EQ(host::grantablePriority(80, 10, upTo(10)), 10);
  EXPECT_EQ(host::grantablePriority(80, 0, upTo(0)), 0);
  EXPECT_EQ(host::grantablePriority(80, 10, upTo(5)), 0) << "refused even at the limit";
  EXPECT_EQ(host::grantablePriority(0, 10, upTo(10)), 0) << "asked for none";
}

/// comply-transport started as a host starts it, asked for receive threads at a priority this
/// process may not have (capabilities are given per program: a host may have more than its
/// transport): it starts at normal priority and says so.
TEST(LiveUnprivileged, ATransportProcessWithoutRealTimeRightsReceivesAtNormalPriority) {
  if (!canDropRealtimeRights()) {
    GTEST_SKIP() << "root without CAP_SETPCAP cannot give up CAP_SYS_NICE for a child";
  }
  constexpr int kChildFd = 3;
  std::array<int, 2> pair{};
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair.data()), 0);
  const std::string log = scratchFile("unprivileged_transport.log");
  const std::string domain = std::to_string(randomDomain());
  const pid_t child = fork();
  if (child == 0) {
    const int file = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    // dup2 onto its own number would leave close-on-exec set.
    const bool moved = pair[1] == kChildFd ? fcntl(kChildFd, F_SETFD, 0) == 0
                                           : dup2(pair[1], kChildFd) == kChildFd;
    if (file < 0 || dup2(file, STDERR_FILENO) < 0 || !moved) {
      _exit(126);
    }
    dropRealtimeRights();
    execl(kTransportProgram.c_str(), kTransportProgram.c_str(), "--fd", "3", "--transport", "dds",
          "--name", "unprivileged", "--domain", domain.c_str(), "--network", "loopback",
          "--priority", "79", "--security", "", nullptr);
    _exit(127);
  }
  ::close(pair[1]);

  transport::process::FrameReader frames;
  std::optional<transport::process::Frame> first;
  std::array<std::uint8_t, 4096> buffer{};
  pollfd readable{pair[0], POLLIN, 0};
  while (!first && ::poll(&readable, 1, 20000) == 1) {
    const ssize_t n = ::recv(pair[0], buffer.data(), buffer.size(), 0);
    if (n <= 0) {
      break;  // the process ended before it said anything
    }
    frames.append({buffer.data(), static_cast<std::size_t>(n)});
    first = frames.next();
  }
  ::close(pair[0]);  // the host's end: the process ends
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);

  const std::string text = textOf(log);
  ASSERT_TRUE(first) << "no frame from comply-transport (status " << status << "):\n" << text;
  EXPECT_EQ(first->kind, transport::process::FrameKind::kReady)
      << std::string(first->payload.begin(), first->payload.end());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status << "\n" << text;
  const std::vector<std::string> warnings = linesWith(text, "warning");
  ASSERT_EQ(warnings.size(), 1U) << text;
  EXPECT_NE(warnings[0].find("no real-time scheduling for the receive threads (SCHED_FIFO "
                             "priority 79"),
            std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace comply::live_test
