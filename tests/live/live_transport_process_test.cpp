// comply run when its middleware dies. DDS runs in a process of its own (comply-transport): a
// peer's sample that crashes CycloneDDS itself, a transport process killed or hung, must leave
// the control loop running, the arm held by the watchdog, and commands applied again once the
// transport is back.
//
// The sample is the one `make fuzz` found (tests/fuzz/upstream/dds_sample/): a malformed XCDR2
// big-endian CartesianCommand that CycloneDDS 0.10.2 byte-swaps past the end of. It is sent as
// the next sample of a live, matched writer, in a hand-built RTPS packet, because no DDS writer
// would serialise it.

#include <arpa/inet.h>
#include <dds/dds.h>
#include <gtest/gtest.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cstring>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "comply/transport/cdr.hpp"
#include "live_support.hpp"
#include "text_file.hpp"

namespace comply::live_test {
namespace {

const std::string kUpstreamCrash =
    kSourceDir + "/tests/fuzz/upstream/dds_sample/xcdr2-big-endian-overrun";
/// Until the transport is back and a command is applied again: the restart delay (0.5 s), the
/// process's start and DDS discovery. A bound for "never came back", with room for a machine
/// busy with a parallel build; the time it took is printed, not asserted.
constexpr auto kBackWithin = 20s;

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// A /proc file's text; empty when the process is gone (textOf would flag that as a failure).
std::string procText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

template <typename T>
void appendLe(std::vector<std::uint8_t>& out, T value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

/// An RTPS message (DDSI-RTPS 2.1, sections 8.3.3 and 8.3.7.2): one DATA submessage carrying
/// `payload` (encapsulation header included) as sample `sequence` of writer `writer`, to every
/// reader matched with it.
std::vector<std::uint8_t> dataPacket(const dds_guid_t& writer, std::int64_t sequence,
                                     const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> packet = {'R', 'T', 'P', 'S', 2, 1, 0x01, 0x10};
  packet.insert(packet.end(), writer.v, writer.v + 12);  // GUID prefix
  packet.push_back(0x15);                                // DATA
  packet.push_back(0x01 | 0x04);                         // little endian, data present
  appendLe<std::uint16_t>(packet, static_cast<std::uint16_t>(20 + payload.size()));
  appendLe<std::uint16_t>(packet, 0);   // extra flags
  appendLe<std::uint16_t>(packet, 16);  // octets to the inline QoS: none, so to the payload
  appendLe<std::uint32_t>(packet, 0);   // reader: unknown, i.e. every matched reader
  packet.insert(packet.end(), writer.v + 12, writer.v + 16);  // writer entity id
  appendLe<std::int32_t>(packet, static_cast<std::int32_t>(sequence >> 32));
  appendLe<std::uint32_t>(packet, static_cast<std::uint32_t>(sequence & 0xFFFFFFFF));
  packet.insert(packet.end(), payload.begin(), payload.end());
  return packet;
}

/// Sends `packet` to `address`, on every user-data unicast port a loopback participant of
/// `domain` can have (DDSI-RTPS 9.6.1.1: 7400 + 250 domain + 11 + 2 index, comply's loopback
/// indices 0..31).
void sendToDomain(int domain, const std::vector<std::uint8_t>& packet,
                  in_addr_t address = htonl(INADDR_LOOPBACK)) {
  const int socket = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(socket, 0);
  for (int index = 0; index < 32; ++index) {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = address;
    to.sin_port = htons(static_cast<std::uint16_t>(7400 + 250 * domain + 11 + 2 * index));
    ::sendto(socket, packet.data(), packet.size(), 0, reinterpret_cast<const sockaddr*>(&to),
             sizeof(to));
  }
  ::close(socket);
}

/// The transport processes `host` started: its children running comply-transport.
std::vector<pid_t> transportProcesses(pid_t host) {
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    const std::string stat = procText(entry.path() / "stat");
    const std::size_t name_end = stat.rfind(')');
    if (name_end == std::string::npos ||
        procText(entry.path() / "cmdline").find("comply-transport") == std::string::npos) {
      continue;
    }
    std::istringstream fields(stat.substr(name_end + 1));
    std::string state;
    pid_t parent = 0;
    fields >> state >> parent;
    if (parent == host) {
      found.push_back(std::stoi(pid));
    }
  }
  return found;
}

/// This machine's first IPv4 address other than loopback, if it has one.
std::optional<in_addr_t> externalAddress() {
  ifaddrs* interfaces = nullptr;
  if (::getifaddrs(&interfaces) != 0) {
    return std::nullopt;
  }
  std::optional<in_addr_t> found;
  for (const ifaddrs* it = interfaces; it != nullptr && !found; it = it->ifa_next) {
    if (it->ifa_addr != nullptr && it->ifa_addr->sa_family == AF_INET &&
        (it->ifa_flags & IFF_LOOPBACK) == 0) {
      found = reinterpret_cast<const sockaddr_in*>(it->ifa_addr)->sin_addr.s_addr;
    }
  }
  ::freeifaddrs(interfaces);
  return found;
}

/// The local address of every IPv4 and IPv6 socket process `pid` holds, as the kernel's tables
/// (/proc/net/udp, tcp, udp6, tcp6, which `ss` prints) give it: hex address ":" hex port.
std::vector<std::string> socketAddresses(pid_t pid) {
  std::set<std::string> inodes;
  for (const auto& fd :
       std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd")) {
    std::error_code error;
    const std::string target = std::filesystem::read_symlink(fd.path(), error).string();
    if (!error && target.rfind("socket:[", 0) == 0) {
      inodes.insert(target.substr(8, target.size() - 9));
    }
  }
  std::vector<std::string> addresses;
  for (const char* table : {"udp", "tcp", "udp6", "tcp6"}) {
    std::istringstream lines(procText(std::string("/proc/net/") + table));
    std::string line;
    std::getline(lines, line);  // the column names
    while (std::getline(lines, line)) {
      std::istringstream fields(line);
      std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
      fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >>
          timeout >> inode;
      if (inodes.count(inode) != 0) {
        addresses.push_back(local);
      }
    }
  }
  return addresses;
}

/// The host as a process, a client, and one sender whose written samples are counted (the
/// injected sample must carry the next sequence number).
class TransportProcessTest : public ::testing::Test {
 protected:
  virtual std::vector<std::string> hostArguments() { return hostArgs(domain_, "crash"); }
  void SetUp() override {
    host_ = std::make_unique<Process>(hostArguments(), log_);
    client_ = std::make_unique<Client>(domain_, "crash");
    connect();
  }
  void TearDown() override { std::filesystem::remove(log_); }

  /// A new sender (a fresh participant); true once the host accounted one of its commands.
  bool connect() {
    writer_.reset();
    sender_.reset();
    sender_ = std::make_unique<transport::Participant>(
        transport::ParticipantOptions{domain_, transport::Network::kLoopback});
    writer_ =
        std::make_unique<transport::Writer<transport::CartesianCommandMessage>>(*sender_, "crash");
    written_ = 0;
    return writer_->waitForMatch(1, 10.0) && applyOne(0.0).has_value();
  }

  /// Sends a valid command holding the arm where it is as the connected writer's next sample, in
  /// a hand-built packet to `address` (as a spoofing peer would); true when the host applied it.
  bool packetApplied(in_addr_t address) {
    const auto state = client_->state(2s);
    if (!state) {
      ADD_FAILURE() << "no state";
      return false;
    }
    const transport::CartesianCommandMessage command =
        poseCommand(*state, {0.0, 0.0, 0.0}, transport::Stamp::now());
    std::vector<std::uint8_t> bytes;
    transport::encodeCdr(command, bytes);
    dds_guid_t guid{};
    EXPECT_EQ(dds_get_guid(writer_->handle(), &guid), DDS_RETCODE_OK);
    sendToDomain(domain_, dataPacket(guid, written_ + 1, bytes), address);
    const bool applied = appliedWithin(command.header.stamp, 1500ms);
    if (applied) {
      ++written_;
    }
    return applied;
  }

  /// Whether the command stamped `stamp` is applied within `timeout`.
  bool appliedWithin(transport::Stamp stamp, std::chrono::milliseconds timeout) {
    const std::int64_t stamp_ns = stamp.nanoseconds();
    return client_->poll(timeout, [&](const auto&) {
      const auto it = client_->outcomes().find(stamp_ns);
      return it != client_->outcomes().end() &&
             it->second.front().outcome == transport::Outcome::kApplied;
    });
  }

  /// Sends the sample as the connected writer's next one.
  void inject() {
    std::vector<std::uint8_t> sample = readBytes(kUpstreamCrash);
    ASSERT_GT(sample.size(), 8U);
    ASSERT_EQ(sample[0] % 5, 0) << "a CartesianCommand (fuzz_dds_sample's topic byte)";
    sample.erase(sample.begin());
    ASSERT_EQ(sample[1], 0x06) << "XCDR2 big endian";
    dds_guid_t guid{};
    ASSERT_EQ(dds_get_guid(writer_->handle(), &guid), DDS_RETCODE_OK);
    sendToDomain(domain_, dataPacket(guid, written_ + 1, sample));
  }

  /// Sends a command holding the arm `dz` [m] above its pose until one is applied; the time it
  /// took, or nullopt when none was applied within kBackWithin.
  std::optional<double> applyOne(double dz) {
    const auto start = Clock::now();
    while (Clock::now() - start < kBackWithin) {
      const auto state = client_->state(200ms);
      if (!state) {
        continue;
      }
      const transport::CartesianCommandMessage command =
          poseCommand(*state, {0.0, 0.0, dz}, transport::Stamp::now());
      writer_->write(command);
      ++written_;
      if (appliedWithin(command.header.stamp, 300ms)) {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }
    }
    return std::nullopt;
  }

  /// The lines of the host's log naming a transport process's end.
  int endsReported() {
    const std::string log = testing::textOf(log_);
    const std::regex ended("the transport process \\(dds, pid [0-9]+\\)");
    return static_cast<int>(
        std::distance(std::sregex_iterator(log.begin(), log.end(), ended), std::sregex_iterator()));
  }

  int domain_ = randomDomain();
  std::string log_ = scratchFile("transport_process.log");
  std::unique_ptr<Process> host_;
  std::unique_ptr<Client> client_;
  std::unique_ptr<transport::Participant> sender_;
  std::unique_ptr<transport::Writer<transport::CartesianCommandMessage>> writer_;
  std::int64_t written_ = 0;
};

TEST_F(TransportProcessTest, ASampleThatCrashesDdsEndsTheTransportProcessNotTheHost) {
  const auto before = client_->state(2s);
  ASSERT_TRUE(before.has_value());

  const auto injected = Clock::now();
  inject();

  // The transport process dies of it; the host reports that and goes on.
  const auto deadline = Clock::now() + 5s;
  while (endsReported() == 0 && Clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_EQ(endsReported(), 1) << testing::textOf(log_);
  EXPECT_NE(testing::textOf(log_).find("ended on signal"), std::string::npos)
      << testing::textOf(log_);
  EXPECT_EQ(host_->wait(0ms), -1) << "the host must still run";

  // Commands flow again once the transport is back: a sender that connects anew, and the one
  // that was connected when it died.
  ASSERT_TRUE(connect()) << "no command applied within " << kBackWithin.count() << " s";
  const double back_s = std::chrono::duration<double>(Clock::now() - injected).count();
  std::printf("applied again %.2f s after the sample\n", back_s);

  // The arm was held meanwhile: where it was, active, no fault.
  const auto after = client_->state(2s);
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(after->state, transport::HostState::kActive);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(after->tcp_position[axis], before->tcp_position[axis], 0.005);
  }
  host_->signal(SIGTERM);
  EXPECT_EQ(host_->wait(10s), 0);
  EXPECT_NE(testing::textOf(log_).find("transport restarts 1"), std::string::npos)
      << testing::textOf(log_);
}

/// The same host with DDS in the host's own process (`--transport dds_inline`).
class TransportInlineTest : public TransportProcessTest {
 protected:
  std::vector<std::string> hostArguments() override {
    std::vector<std::string> args = TransportProcessTest::hostArguments();
    args.insert(args.end(), {"--transport", "dds_inline"});
    return args;
  }
};

// What the sample does to a host that deserialises in its own process (the transport the host
// had before): it dies with CycloneDDS, and the arm with it. Should a CycloneDDS release stop
// crashing on it, this fails, and the sample is then a regression input of fuzz_dds_sample.
TEST_F(TransportInlineTest, TheSameSampleKillsAHostThatRunsDdsInItsOwnProcess) {
  inject();
  const int code = host_->wait(5s);
  EXPECT_GT(code, 128) << "a host with DDS inline survived the sample: " << testing::textOf(log_);
}

// Loopback means loopback: no socket of the host or its transport process listens on another
// address, and a command sent to the machine's external address does not arrive, while the same
// packet to 127.0.0.1 is applied (so the packet itself is good).
TEST_F(TransportProcessTest, TheDefaultHostListensOnLoopbackOnly) {
  const std::vector<pid_t> transports = transportProcesses(host_->pid());
  ASSERT_EQ(transports.size(), 1U);
  std::vector<std::string> addresses = socketAddresses(transports.front());
  ASSERT_GE(addresses.size(), 2U) << "the transport process's DDS sockets";
  for (const std::string& address : socketAddresses(host_->pid())) {
    addresses.push_back(address);
  }
  for (const std::string& address : addresses) {
    EXPECT_EQ(address.substr(0, 9), "0100007F:") << address << ": not 127.0.0.1";
  }
  const auto external = externalAddress();
  if (!external) {
    GTEST_SKIP() << "this machine has no address other than loopback to spoof";
  }
  EXPECT_FALSE(packetApplied(*external)) << "a packet to the external address was applied";
  EXPECT_TRUE(packetApplied(htonl(INADDR_LOOPBACK)));
}

// Before: CycloneDDS in the host bound every socket to every address, and the packet to the
// external address was applied.
TEST_F(TransportInlineTest, TheHostListensOnEveryAddressWhenDdsRunsInIt) {
  const auto external = externalAddress();
  if (!external) {
    GTEST_SKIP() << "this machine has no address other than loopback to spoof";
  }
  bool any_address = false;
  for (const std::string& address : socketAddresses(host_->pid())) {
    any_address = any_address || address.substr(0, 9) == "00000000:";
  }
  EXPECT_TRUE(any_address);
  EXPECT_TRUE(packetApplied(*external));
}

TEST_F(TransportProcessTest, AKilledOrHungTransportProcessIsStartedAgain) {
  for (const int signal : {SIGKILL, SIGSTOP}) {
    const std::vector<pid_t> transports = transportProcesses(host_->pid());
    ASSERT_EQ(transports.size(), 1U);
    const int ends = endsReported();
    ::kill(transports.front(), signal);
    // A hung process is found by its missing heartbeat (1 s), a dead one at once.
    const auto deadline = Clock::now() + 5s;
    while (endsReported() == ends && Clock::now() < deadline) {
      std::this_thread::sleep_for(20ms);
    }
    ASSERT_EQ(endsReported(), ends + 1) << testing::textOf(log_);
    ASSERT_TRUE(applyOne(0.0).has_value() || connect()) << testing::textOf(log_);
    EXPECT_EQ(host_->wait(0ms), -1);
  }
  EXPECT_NE(testing::textOf(log_).find("stopped answering"), std::string::npos)
      << testing::textOf(log_);
  // A process started again by the host's reader thread outlives that thread: the shutdown
  // flushes through it, with no end reported, and the summary counts both restarts.
  const int ends = endsReported();
  host_->signal(SIGTERM);
  EXPECT_EQ(host_->wait(10s), 0);
  EXPECT_EQ(endsReported(), ends) << testing::textOf(log_);
  EXPECT_NE(testing::textOf(log_).find("transport restarts 2"), std::string::npos)
      << testing::textOf(log_);
}

}  // namespace
}  // namespace comply::live_test
