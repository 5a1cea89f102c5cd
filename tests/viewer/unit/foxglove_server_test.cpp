// The Foxglove server over real sockets, with a Beast client: both subprotocol names and the
// refusal of others, the greeting, subscriptions, latched and rate-limited channels, a client
// that stops reading (its big channel dropped and said, its small one whole), bad input.

#include "comply/viewer/foxglove_server.hpp"

#include <gtest/gtest.h>

#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <thread>

#include "ws_test_client.hpp"

namespace comply::viewer {
namespace {

using testing::WsTestClient;
using namespace std::chrono_literals;

ChannelSpec channel(const std::string& topic, double max_rate_hz = 0.0, bool latched = false) {
  return {.topic = topic,
          .encoding = "cdr",
          .schema_name = "pkg/msg/T",
          .schema_encoding = "ros2msg",
          .schema = "uint8 x\n",
          .max_rate_hz = max_rate_hz,
          .latched = latched};
}

ServerOptions anyPort() {
  return {.address = "127.0.0.1", .port = 0};
}

/// Waits for the server to take a client's subscription (it reads it on its own thread).
bool waitUntilWanted(FoxgloveServer& server, ChannelId id) {
  for (int i = 0; i < 400 && !server.wants(id); ++i) {
    std::this_thread::sleep_for(5ms);
  }
  return server.wants(id);
}

std::vector<std::uint8_t> bytes(const std::string& text) {
  return {text.begin(), text.end()};
}

TEST(FoxgloveServer, BothSubprotocolNamesAreAcceptedAndGreeted) {
  FoxgloveServer server(anyPort());
  server.addChannel(channel("/a"));
  for (const std::string name : {"foxglove.sdk.v1", "foxglove.websocket.v1"}) {
    WsTestClient client(server.port(), name);
    EXPECT_EQ(client.protocol(), name);
    const auto info = client.readJson();
    EXPECT_EQ(info["op"], "serverInfo");
    EXPECT_EQ(info["name"], "comply");
    const auto advertise = client.readJson();
    EXPECT_EQ(advertise["op"], "advertise");
    ASSERT_EQ(advertise["channels"].size(), 1U);
    EXPECT_EQ(advertise["channels"][0]["topic"], "/a");
  }
}

TEST(FoxgloveServer, OtherSubprotocolsArePlainRequestsAreAnswered) {
  FoxgloveServer server(anyPort());
  EXPECT_THROW(WsTestClient(server.port(), "foxglove.other.v9"), boost::system::system_error);
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  boost::asio::write(socket, boost::asio::buffer(std::string("GET / HTTP/1.1\r\nHost: x\r\n\r\n")));
  std::string reply;
  boost::system::error_code error;
  boost::asio::read(socket, boost::asio::dynamic_buffer(reply), error);
  EXPECT_NE(reply.find("HTTP/1.1 200"), std::string::npos) << reply;
  EXPECT_NE(reply.find("Foxglove WebSocket server"), std::string::npos) << reply;
  EXPECT_NE(reply.find(server.url()), std::string::npos) << reply;
}

TEST(FoxgloveServer, ASubscriberGetsTheChannelsMessagesWithItsSubscriptionAndTime) {
  FoxgloveServer server(anyPort());
  const ChannelId a = server.addChannel(channel("/a"));
  const ChannelId b = server.addChannel(channel("/b"));
  EXPECT_FALSE(server.wants(a)) << "nobody subscribes yet";
  EXPECT_FALSE(server.publish(a, 1, bytes("lost")));
  WsTestClient client(server.port(), "foxglove.sdk.v1");
  client.readJson();
  client.readJson();
  client.subscribe(42, b);
  ASSERT_TRUE(waitUntilWanted(server, b));
  EXPECT_FALSE(server.wants(a));
  EXPECT_EQ(server.clients(), 1U);
  EXPECT_TRUE(server.publish(b, 123456789012345, bytes("hello")));
  const testing::WsMessage message = client.read();
  ASSERT_FALSE(message.text);
  EXPECT_EQ(message.data[0], 0x01);
  EXPECT_EQ(message.subscription(), 42U);
  EXPECT_EQ(message.logTime(), 123456789012345U);
  EXPECT_EQ(message.payload(), "hello");
  client.send(R"({"op":"unsubscribe","subscriptionIds":[42]})");
  for (int i = 0; i < 400 && server.wants(b); ++i) {
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_FALSE(server.wants(b));
  client.close();
  for (int i = 0; i < 400 && server.clients() > 0; ++i) {
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(server.clients(), 0U);
}

TEST(FoxgloveServer, ALatchedChannelsLastMessageGoesToEveryNewSubscriber) {
  FoxgloveServer server(anyPort());
  const ChannelId description = server.addChannel(channel("/robot_description", 0, true));
  server.publish(description, 7, bytes("first"));
  server.publish(description, 8, bytes("urdf"));
  for (int round = 0; round < 2; ++round) {
    WsTestClient client(server.port(), "foxglove.sdk.v1");
    client.readJson();
    client.readJson();
    client.subscribe(1, description);
    const testing::WsMessage message = client.read();
    EXPECT_EQ(message.payload(), "urdf");
    EXPECT_EQ(message.logTime(), 8U);
  }
}

TEST(FoxgloveServer, AChannelsRateLimitRefusesAndCounts) {
  FoxgloveServer server(anyPort());
  const ChannelId limited = server.addChannel(channel("/limited", 10.0));
  WsTestClient client(server.port(), "foxglove.sdk.v1");
  client.subscribe(0, limited);
  ASSERT_TRUE(waitUntilWanted(server, limited));
  int accepted = 0;
  for (int i = 0; i < 50; ++i) {
    accepted += server.publish(limited, i, bytes("x")) ? 1 : 0;
  }
  EXPECT_EQ(accepted, 1) << "50 messages within far less than 0.05 s";
  EXPECT_FALSE(server.wants(limited));
  std::this_thread::sleep_for(120ms);
  EXPECT_TRUE(server.wants(limited));
  EXPECT_TRUE(server.publish(limited, 99, bytes("y")));
  const ChannelStats stats = server.stats().at(limited);
  EXPECT_EQ(stats.published, 2U);
  EXPECT_EQ(stats.rate_limited, 50U) << "49 publish() and one wants() refused";
}

TEST(FoxgloveServer, AClientThatStopsReadingLosesTheBigChannelNotTheSmallOne) {
  FoxgloveServer server({.address = "127.0.0.1", .port = 0, .channel_queue_bytes = 256 * 1024});
  const ChannelId big = server.addChannel(channel("/big"));
  const ChannelId small = server.addChannel(channel("/small"));
  WsTestClient client(server.port(), "foxglove.sdk.v1");
  client.readJson();
  client.readJson();
  client.subscribe(0, big);
  client.subscribe(1, small);
  ASSERT_TRUE(waitUntilWanted(server, big));
  ASSERT_TRUE(waitUntilWanted(server, small));
  // 40 MB on the big channel while the client reads nothing: far more than the queue and the
  // sockets' buffers hold.
  const std::vector<std::uint8_t> block(20000, 0xab);
  for (int i = 0; i < 2000; ++i) {
    server.publish(big, i, block);
    if (i % 10 == 0) {
      const std::string number = std::to_string(i / 10);
      server.publish(small, i, bytes(number));
    }
  }
  std::this_thread::sleep_for(1500ms);  // a drop report goes out once a second
  int next_small = 0;
  int big_received = 0;
  bool warned = false;
  while (next_small < 200 || !warned) {
    const testing::WsMessage message = client.read();
    if (message.text) {
      const auto status = message.json();
      if (status["op"] == "status" && status["level"] == 1) {
        EXPECT_NE(status["message"].get<std::string>().find("/big"), std::string::npos);
        EXPECT_EQ(status["message"].get<std::string>().find("/small"), std::string::npos);
        warned = true;
      }
    } else if (message.subscription() == 1) {
      EXPECT_EQ(message.payload(), std::to_string(next_small)) << "a small message lost";
      ++next_small;
    } else {
      ++big_received;
    }
  }
  const std::vector<ChannelStats> stats = server.stats();
  EXPECT_GT(stats[big].dropped, 1000U);
  EXPECT_EQ(stats[small].dropped, 0U);
  EXPECT_LT(big_received, 2000);
}

TEST(FoxgloveServer, WhatItCannotTakeIsAnsweredWithAnError) {
  FoxgloveServer server(anyPort());
  server.addChannel(channel("/a"));
  WsTestClient client(server.port(), "foxglove.sdk.v1");
  client.readJson();
  client.readJson();
  const auto expectError = [&](const std::string& part) {
    const auto status = client.readJson();
    EXPECT_EQ(status["op"], "status");
    EXPECT_EQ(status["level"], 2);
    EXPECT_NE(status["message"].get<std::string>().find(part), std::string::npos)
        << status["message"];
  };
  client.send("{not json");
  expectError("not a JSON object");
  client.subscribe(0, 9);
  expectError("no channel 9");
  client.subscribe(0, 0);
  client.subscribe(0, 0);
  expectError("already in use");
  client.send(R"({"op":"setParameters","parameters":[]})");
  expectError("does not take \"setParameters\"");
  client.sendBinary(std::string("\x01\x00\x00\x00\x00", 5));
  expectError("takes no messages");
}

TEST(FoxgloveServer, AnAddressItCannotListenOnIsNamed) {
  FoxgloveServer first(anyPort());
  try {
    FoxgloveServer second({.address = "127.0.0.1", .port = first.port()});
    FAIL() << "two servers on one port";
  } catch (const ViewerError& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(first.port())),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW(FoxgloveServer({.address = "localhost:x", .port = 0}), ViewerError);
  EXPECT_EQ(first.url(), "ws://127.0.0.1:" + std::to_string(first.port()));
}

}  // namespace
}  // namespace comply::viewer
