// One client's queues: protocol text first, channels in turn, the oldest dropped past the bound.

#include "client_queue.hpp"

#include <gtest/gtest.h>

namespace comply::viewer {
namespace {

SharedPayload bytes(std::size_t size, std::uint8_t value = 0) {
  return std::make_shared<const std::vector<std::uint8_t>>(size, value);
}

ChannelId channelOf(const Outgoing& out) {
  return std::get<OutgoingData>(out).channel;
}

TEST(ClientQueue, MessageDataHeaderIsTheProtocolsLittleEndianLayout) {
  const auto header = messageDataHeader(0x01020304U, 0x0102030405060708LL);
  const std::array<std::uint8_t, 13> expected{0x01, 0x04, 0x03, 0x02, 0x01, 0x08, 0x07,
                                              0x06, 0x05, 0x04, 0x03, 0x02, 0x01};
  EXPECT_EQ(header, expected);
}

TEST(ClientQueue, TextGoesBeforeDataAndDataCarriesTheClientsSubscription) {
  ClientQueue queue(1 << 20);
  ASSERT_TRUE(queue.subscribe(3, 77));
  queue.push(3, 5, bytes(10, 9));
  queue.pushText("advertise");
  Outgoing out;
  ASSERT_TRUE(queue.pop(out));
  EXPECT_EQ(std::get<OutgoingText>(out).text, "advertise");
  ASSERT_TRUE(queue.pop(out));
  const auto& data = std::get<OutgoingData>(out);
  EXPECT_EQ(data.channel, 3U);
  EXPECT_EQ(data.header, messageDataHeader(77, 5));
  EXPECT_EQ(data.payload->size(), 10U);
  EXPECT_FALSE(queue.pop(out));
}

TEST(ClientQueue, TextsWaitingAreBounded) {
  ClientQueue queue(1 << 20);
  for (std::size_t i = 0; i < ClientQueue::kMaxTexts; ++i) {
    ASSERT_TRUE(queue.pushText("status"));
  }
  EXPECT_FALSE(queue.pushText("one more"));
  Outgoing out;
  ASSERT_TRUE(queue.pop(out));
  EXPECT_TRUE(queue.pushText("room again"));
}

TEST(ClientQueue, AMessageOfAnotherChannelIsWrittenWithinOneRoundOfABigBacklog) {
  ClientQueue queue(1 << 30);
  ASSERT_TRUE(queue.subscribe(1, 0));
  ASSERT_TRUE(queue.subscribe(2, 1));
  for (int i = 0; i < 1000; ++i) {
    queue.push(1, i, bytes(1000));
  }
  Outgoing out;
  ASSERT_TRUE(queue.pop(out));
  EXPECT_EQ(channelOf(out), 1U);
  queue.push(2, 0, bytes(10));
  ASSERT_TRUE(queue.pop(out));
  EXPECT_EQ(channelOf(out), 2U) << "the small channel waited behind the big one's backlog";
  ASSERT_TRUE(queue.pop(out));
  EXPECT_EQ(channelOf(out), 1U);
}

TEST(ClientQueue, PastItsBoundAChannelDropsItsOldestAndCountsThem) {
  ClientQueue queue(1000);
  ASSERT_TRUE(queue.subscribe(1, 0));
  ASSERT_TRUE(queue.subscribe(2, 1));
  std::uint64_t dropped = 0;
  for (int i = 0; i < 25; ++i) {
    dropped += queue.push(1, i, bytes(100));
  }
  queue.push(2, 0, bytes(10));
  EXPECT_EQ(dropped, 15U);
  EXPECT_EQ(queue.queuedBytes(1), 1000U);
  EXPECT_EQ(queue.queuedBytes(2), 10U);
  const std::vector<DropReport> drops = queue.takeDrops();
  ASSERT_EQ(drops.size(), 1U);
  EXPECT_EQ(drops[0].channel, 1U);
  EXPECT_EQ(drops[0].dropped, 15U);
  EXPECT_TRUE(queue.takeDrops().empty()) << "a report is taken once";
  // What stays is the newest ten, in order.
  std::vector<std::uint64_t> times;
  Outgoing out;
  while (queue.pop(out)) {
    const auto& data = std::get<OutgoingData>(out);
    if (data.channel == 1) {
      std::uint64_t time = 0;
      for (int b = 7; b >= 0; --b) {
        time = (time << 8) | data.header[5 + b];
      }
      times.push_back(time);
    }
  }
  ASSERT_EQ(times.size(), 10U);
  EXPECT_EQ(times.front(), 15U);
  EXPECT_EQ(times.back(), 24U);
}

TEST(ClientQueue, AMessageLargerThanTheBoundStillGoes) {
  ClientQueue queue(100);
  ASSERT_TRUE(queue.subscribe(1, 0));
  EXPECT_EQ(queue.push(1, 0, bytes(5000)), 0U);
  EXPECT_EQ(queue.push(1, 1, bytes(5000)), 1U);
  Outgoing out;
  ASSERT_TRUE(queue.pop(out));
  EXPECT_EQ(std::get<OutgoingData>(out).payload->size(), 5000U);
  EXPECT_FALSE(queue.pop(out));
}

TEST(ClientQueue, SubscriptionsAreOnePerChannelAndIdsAreNotReused) {
  ClientQueue queue(1000);
  EXPECT_TRUE(queue.subscribe(1, 10));
  EXPECT_FALSE(queue.subscribe(1, 11)) << "the channel twice";
  EXPECT_FALSE(queue.subscribe(2, 10)) << "the id twice";
  EXPECT_EQ(queue.push(5, 0, bytes(1)), 0U);  // not subscribed: nothing queued
  Outgoing out;
  EXPECT_FALSE(queue.pop(out));
  queue.push(1, 0, bytes(1));
  EXPECT_EQ(queue.unsubscribe(10), std::optional<ChannelId>(1));
  EXPECT_EQ(queue.unsubscribe(10), std::nullopt);
  EXPECT_FALSE(queue.pop(out)) << "an unsubscribed channel's queue goes with it";
  EXPECT_TRUE(queue.subscribe(2, 10));
  EXPECT_EQ(queue.channels(), std::vector<ChannelId>{2});
}

}  // namespace
}  // namespace comply::viewer
