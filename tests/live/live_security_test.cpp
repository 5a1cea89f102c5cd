// comply run with DDS Security: a keystore made by scripts/create-keystore.sh (SROS2's layout),
// the host on its enclave. A participant without credentials never matches the host, so its
// commands never arrive; one with a monitor's credentials may not write a command; one with the
// client enclave's credentials is applied. Before, any process that could reach the host's ports
// could command the arm.

#include <gtest/gtest.h>

#include <cstdlib>

#include "live_support.hpp"
#include "text_file.hpp"

namespace comply::live_test {
namespace {

class LiveSecurity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::filesystem::remove_all(keystore());
    const std::string command = kSourceDir + "/scripts/create-keystore.sh " + keystore().string() +
                                " /comply/host=host /comply/client=client /comply/ui=monitor"
                                " > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command << " (needs openssl)";
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(keystore()); }
  static std::filesystem::path keystore() {
    return std::filesystem::temp_directory_path() /
           ("comply_keystore_" + std::to_string(::getpid()));
  }
  static std::filesystem::path enclave(const std::string& name) {
    return keystore() / "enclaves" / "comply" / name;
  }

  void SetUp() override {
    std::vector<std::string> args = hostArgs(domain_, "secure");
    args.insert(args.end(), {"--security", enclave("host").string()});
    host_ = std::make_unique<Process>(args, log_);
    client_ = std::make_unique<Client>(domain_, "secure", enclave("client"));
  }
  void TearDown() override { std::filesystem::remove(log_); }

  // DDS Security admits domains 0..230; randomDomain() draws from 1..230.
  int domain_ = randomDomain();
  std::string log_ = scratchFile("security.log");
  std::unique_ptr<Process> host_;
  std::unique_ptr<Client> client_;
};

TEST_F(LiveSecurity, AnUnauthenticatedWriterNeverArrivesAnAuthenticatedOneIsApplied) {
  const auto state = client_->state(10s);
  ASSERT_TRUE(state.has_value()) << "the secure client hears the secure host";

  // No credentials (`comply send` without --security, a process of its own: CycloneDDS holds
  // every participant of a process on a domain to the same security): discovery and every topic
  // are encrypted, so it never finds the host, and nothing it writes arrives.
  // Where the arm is: a command the host would apply.
  const std::string json = "{\"position\": [" + std::to_string(state->tcp_position[0]) + ", " +
                           std::to_string(state->tcp_position[1]) + ", " +
                           std::to_string(state->tcp_position[2]) + "]}";
  Process plain({"send", "--domain", std::to_string(domain_), "--name", "secure", "--timeout", "3",
                 "--json", json});
  EXPECT_NE(plain.wait(20s), 0) << "a client without credentials finds no host";
  ASSERT_TRUE(client_->poll(2s, [](const auto&) { return true; }));
  EXPECT_EQ(client_->last().commands_received, 0U);

  // The client enclave's credentials: matched and applied.
  transport::Participant member({.domain_id = domain_, .security = enclave("client")});
  transport::Writer<transport::CartesianCommandMessage> writer(member, "secure");
  ASSERT_TRUE(writer.waitForMatch(1, 10.0));
  ASSERT_TRUE(handshake(writer, *client_, static_cast<int>(state->position.size())));
  const transport::CartesianCommandMessage command =
      poseCommand(*state, {0.0, 0.0, 0.0}, transport::Stamp::now());
  ASSERT_TRUE(writer.write(command));
  const std::int64_t stamp = command.header.stamp.nanoseconds();
  ASSERT_TRUE(client_->poll(5s, [&](const auto&) { return client_->outcomes().count(stamp) > 0; }));
  EXPECT_EQ(client_->outcomes().at(stamp).front().outcome, transport::Outcome::kApplied);
  // Only the member's commands were ever received: the handshake's and this one.
  ASSERT_TRUE(client_->poll(2s, [](const auto&) { return true; }));
  EXPECT_EQ(client_->last().commands_received,
            client_->last().commands_applied + client_->last().commands_rejected);
  EXPECT_LE(client_->last().commands_received, 101U);  // the handshake sends at most 100
  EXPECT_EQ(client_->last().commands_rejected, 0U);

  // A monitor's credentials (a dashboard's): it may read, not command. Its command topic is
  // refused by access control, so `comply send` fails before sending anything.
  Process monitor_send({"send", "--domain", std::to_string(domain_), "--name", "secure",
                        "--security", enclave("ui").string(), "--json", json},
                       log_ + ".monitor");
  EXPECT_NE(monitor_send.wait(20s), 0);
  const std::string said = testing::textOf(log_ + ".monitor");
  EXPECT_NE(said.find("Not Allowed By Security"), std::string::npos) << said;
  std::filesystem::remove(log_ + ".monitor");
  // `comply send` with the client's credentials: applied (exit 0).
  Process member_send({"send", "--domain", std::to_string(domain_), "--name", "secure",
                       "--security", enclave("client").string(), "--json", json});
  EXPECT_EQ(member_send.wait(30s), 0);
  host_->signal(SIGTERM);
  EXPECT_EQ(host_->wait(10s), 0);
  EXPECT_NE(testing::textOf(log_).find("DDS Security as " + enclave("host").string()),
            std::string::npos)
      << testing::textOf(log_);
}

TEST_F(LiveSecurity, AHostWithoutItsFilesSaysWhichIsMissing) {
  host_->signal(SIGKILL);
  host_->wait(5s);
  const std::string missing = (keystore() / "enclaves" / "nowhere").string();
  std::vector<std::string> args = hostArgs(domain_, "secure");
  args.insert(args.end(), {"--security", missing, "--duration", "1"});
  Process host(args, log_);
  EXPECT_GT(host.wait(20s), 0);
  EXPECT_NE(testing::textOf(log_).find(missing + "/identity_ca.cert.pem is not there"),
            std::string::npos)
      << testing::textOf(log_);
}

}  // namespace
}  // namespace comply::live_test
