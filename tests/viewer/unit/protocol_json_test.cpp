// The protocol's text messages and the subprotocol negotiation.

#include "protocol_json.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace comply::viewer {
namespace {

TEST(Subprotocol, BothNamesAreServedInTheClientsOrder) {
  EXPECT_EQ(chooseSubprotocol("foxglove.sdk.v1"), "foxglove.sdk.v1");
  EXPECT_EQ(chooseSubprotocol("foxglove.websocket.v1"), "foxglove.websocket.v1");
  EXPECT_EQ(chooseSubprotocol("x.v1, foxglove.websocket.v1,foxglove.sdk.v1"),
            "foxglove.websocket.v1");
  EXPECT_EQ(chooseSubprotocol(" foxglove.sdk.v1 "), "foxglove.sdk.v1");
}

TEST(Subprotocol, OthersAreRefused) {
  EXPECT_EQ(chooseSubprotocol(""), std::nullopt);
  EXPECT_EQ(chooseSubprotocol("foxglove.sdk.v2"), std::nullopt);
  EXPECT_EQ(chooseSubprotocol("foxglove.websocket.v1x, ,"), std::nullopt);
}

TEST(ServerMessages, AdvertiseListsEveryChannelAsTheProtocolNamesIt) {
  const auto message = nlohmann::json::parse(advertiseJson({{4,
                                                             {.topic = "/a",
                                                              .encoding = "cdr",
                                                              .schema_name = "pkg/msg/A",
                                                              .schema_encoding = "ros2msg",
                                                              .schema = "float64 x\n"}}}));
  EXPECT_EQ(message["op"], "advertise");
  ASSERT_EQ(message["channels"].size(), 1U);
  const auto& channel = message["channels"][0];
  EXPECT_EQ(channel["id"], 4);
  EXPECT_EQ(channel["topic"], "/a");
  EXPECT_EQ(channel["encoding"], "cdr");
  EXPECT_EQ(channel["schemaName"], "pkg/msg/A");
  EXPECT_EQ(channel["schemaEncoding"], "ros2msg");
  EXPECT_EQ(channel["schema"], "float64 x\n");
  const auto info = nlohmann::json::parse(serverInfoJson("comply", "s-1"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "comply");
  EXPECT_TRUE(info["capabilities"].empty()) << "it takes nothing from clients";
  const auto status = nlohmann::json::parse(statusJson(StatusLevel::kWarning, "slow"));
  EXPECT_EQ(status["level"], 1);
  EXPECT_EQ(status["message"], "slow");
}

TEST(ClientMessages, SubscribeAndUnsubscribeAreRead) {
  const ClientOp subscribe = parseClientOp(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":4294967295,"channelId":0}]})");
  const auto& subscriptions = std::get<SubscribeOp>(subscribe).subscriptions;
  ASSERT_EQ(subscriptions.size(), 2U);
  EXPECT_EQ(subscriptions[0], std::make_pair(SubscriptionId{0}, ChannelId{3}));
  EXPECT_EQ(subscriptions[1].first, 4294967295U);
  const ClientOp unsubscribe = parseClientOp(R"({"op":"unsubscribe","subscriptionIds":[7, 8]})");
  EXPECT_EQ(std::get<UnsubscribeOp>(unsubscribe).subscriptions,
            (std::vector<SubscriptionId>{7, 8}));
  EXPECT_EQ(std::get<OtherOp>(parseClientOp(R"({"op":"advertise","channels":[]})")).op,
            "advertise");
}

TEST(ClientMessages, MalformedOnesAreRefusedSayingWhat) {
  const auto refusal = [](std::string_view text) {
    try {
      parseClientOp(text);
    } catch (const ProtocolError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("not json"), "not a JSON object");
  EXPECT_EQ(refusal("[1]"), "not a JSON object");
  EXPECT_EQ(refusal(R"({"subscriptions":[]})"), "no \"op\" string");
  EXPECT_EQ(refusal(R"({"op":"subscribe","subscriptions":{}})"),
            "subscribe: \"subscriptions\" must be an array");
  EXPECT_EQ(refusal(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":0}]})"),
            "subscribe: \"id\" must be a non-negative integer");
  EXPECT_EQ(refusal(R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":0}]})"),
            "subscribe: \"id\" is out of range");
  EXPECT_EQ(refusal(R"({"op":"subscribe","subscriptions":[{"id":1}]})"),
            "subscribe: \"channelId\" must be a non-negative integer");
  EXPECT_EQ(refusal(R"({"op":"unsubscribe","subscriptionIds":["1"]})"),
            "unsubscribe: subscription ids must be non-negative integers");
}

}  // namespace
}  // namespace comply::viewer
