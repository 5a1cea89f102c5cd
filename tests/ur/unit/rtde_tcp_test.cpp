// RTDE over loopback TCP: comply's client against the emulator's server at the controller's
// 500 Hz, every package in order, a slower recipe decimated, inputs written and kept, refusals.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "comply/ur/rtde_client.hpp"
#include "comply/ur/rtde_server.hpp"

namespace comply::ur {
namespace {

using namespace std::chrono_literals;

std::map<std::string, RtdeValue> cycleVariables(int i) {
  const double q = 0.001 * i;
  return {{"timestamp", 0.002 * i},
          {"actual_q", std::array<double, 6>{q, -q, q, -q, q, -q}},
          {"robot_mode", std::int32_t{7}}};
}

/// The controller's cycles 0 .. count-1 at 500 Hz from this thread.
void runCycles(RtdeServer& server, int count) {
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) {
    server.sendOutputs(cycleVariables(i));
    next += 2ms;
    std::this_thread::sleep_until(next);
  }
}

TEST(RtdeTcp, EveryOutputPackageArrivesInOrderAndInputsReachTheController) {
  RtdeServer server({.address = "127.0.0.1", .port = 0});
  RtdeClient client("127.0.0.1", server.port());
  EXPECT_EQ(client.controllerVersion().minor, 23U);
  const Recipe output = client.setupOutputs(500, {"timestamp", "actual_q", "robot_mode"});
  EXPECT_EQ(output.types,
            (std::vector<RtdeType>{RtdeType::kDouble, RtdeType::kVector6d, RtdeType::kInt32}));
  const Recipe input = client.setupInputs({"input_double_register_0", "input_int_register_0"});
  client.start();
  std::jthread controller([&] { runCycles(server, 1000); });
  std::vector<RtdeValue> values;
  int received = 0;
  while (client.receive(values, 1.0)) {
    const auto expected = cycleVariables(received);
    const std::vector<RtdeValue> in_order{expected.at("timestamp"), expected.at("actual_q"),
                                          expected.at("robot_mode")};
    if (values != in_order) {
      ADD_FAILURE() << "package " << received << " is not cycle " << received << "'s";
      break;  // the controller thread is joined below
    }
    if (received == 10) {
      client.send(input, {0.75, std::int32_t{-4}});
    }
    if (++received == 1000) {
      break;
    }
  }
  controller.join();
  EXPECT_EQ(received, 1000) << "packages lost or late by more than a second";
  EXPECT_EQ(server.inputs().at("input_double_register_0"), RtdeValue{0.75});
  EXPECT_EQ(server.inputs().at("input_int_register_0"), RtdeValue{std::int32_t{-4}});
  EXPECT_EQ(server.connections(), 1U);
}

TEST(RtdeTcp, ASlowerRecipeGetsEveryNthCycle) {
  RtdeServer server({.address = "127.0.0.1", .port = 0});
  RtdeClient client("127.0.0.1", server.port());
  client.setupOutputs(125, {"timestamp"});
  client.start();
  std::jthread controller([&] { runCycles(server, 400); });
  std::vector<RtdeValue> values;
  std::vector<double> stamps;
  while (stamps.size() < 100 && client.receive(values, 1.0)) {
    stamps.push_back(std::get<double>(values.at(0)));
  }
  controller.join();
  ASSERT_EQ(stamps.size(), 100U);
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    EXPECT_DOUBLE_EQ(stamps[k], 0.008 * static_cast<double>(k)) << k;
  }
}

TEST(RtdeTcp, RefusalsComeBackNamed) {
  RtdeServer server({.address = "127.0.0.1", .port = 0});
  RtdeClient client("127.0.0.1", server.port());
  try {
    client.setupOutputs(500, {"timestamp", "actual_joint_velocity"});
    FAIL() << "a variable the controller lacks was accepted";
  } catch (const RtdeError& error) {
    EXPECT_STREQ(error.what(),
                 "recipe refused: actual_joint_velocity: the controller has no such variable");
  }
  try {
    client.setupOutputs(1000, {"timestamp"});
    FAIL() << "1 kHz was accepted";
  } catch (const RtdeError& error) {
    EXPECT_NE(std::string(error.what()).find("recipe refused: timestamp"), std::string::npos);
  }
  ASSERT_FALSE(client.messages().empty());
  EXPECT_NE(client.messages().back().message.find("serves up to 500"), std::string::npos);
  const std::uint16_t closed = [] {
    RtdeServer gone({.address = "127.0.0.1", .port = 0});
    return gone.port();
  }();
  EXPECT_THROW(RtdeClient("127.0.0.1", closed, 0.5), RtdeError);
  EXPECT_THROW(RtdeClient("localhost", server.port()), RtdeError);
}

}  // namespace
}  // namespace comply::ur
