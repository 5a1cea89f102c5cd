// What a reader takes off the wire is held to the bounds of a command, where it is read: a
// header.frame_id longer than kMaxFrameIdBytes and a chunk of more than kMaxChunkWaypoints reach
// the host as refused (with the reason its outcome gives), their stamp kept so that the sender
// hears of them, and none of the long text kept. Stamps past what int32 seconds hold saturate
// instead of wrapping into the past.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "comply/transport/endpoints.hpp"
#include "comply/transport/in_process.hpp"
#include "loopback.hpp"

namespace comply::transport {
namespace {

template <typename Message>
Sample<Message> roundTrip(const Message& message) {
  Loopback<Message> loopback("bounds");
  loopback.send(message);
  std::vector<Sample<Message>> samples;
  EXPECT_EQ(loopback.reader.take(samples), 1U);
  return samples.empty() ? Sample<Message>{} : samples.front();
}

TEST(TransportBounds, AFrameIdOverItsBoundIsRefusedWhereItIsRead) {
  CartesianCommandMessage message;
  message.header = {{1700000000, 5}, std::string(257, 'x')};
  message.command = CartesianCommand::zero(7);
  const Sample<CartesianCommandMessage> got = roundTrip(message);
  EXPECT_NE(got.malformed.find("header.frame_id is 257 bytes, more than 256"), std::string::npos)
      << got.malformed;
  EXPECT_EQ(got.malformed_reason, Reason::kTooLarge);
  EXPECT_TRUE(got.message.header.frame_id.empty()) << "the long text was kept";
  EXPECT_EQ(got.message.header.stamp, message.header.stamp) << "the outcome needs the stamp";

  message.header.frame_id = std::string(256, 'x');  // at the bound: taken
  const Sample<CartesianCommandMessage> taken = roundTrip(message);
  EXPECT_TRUE(taken.malformed.empty()) << taken.malformed;
  EXPECT_EQ(taken.message.header.frame_id, message.header.frame_id);
}

TEST(TransportBounds, TheInProcessBusHoldsAFrameIdToTheSameBound) {
  const std::shared_ptr<InProcessBus> bus = InProcessBus::named("transport_bounds");
  RequestMessage request;
  request.header = {{1700000000, 5}, std::string(1000, 'x')};
  request.request = RequestType::kDeactivate;
  bus->send(request, 7);
  Inbox inbox;
  bus->receive(inbox, 1.0);
  ASSERT_EQ(inbox.requests.size(), 1U);
  EXPECT_EQ(inbox.requests[0].malformed_reason, Reason::kTooLarge);
  EXPECT_NE(inbox.requests[0].malformed.find("header.frame_id is 1000 bytes"), std::string::npos)
      << inbox.requests[0].malformed;
  EXPECT_TRUE(inbox.requests[0].message.header.frame_id.empty());
}

TEST(TransportBounds, AChunkOfMoreWaypointsThanAllowedReachesTheReaderAsInvalid) {
  JointChunkMessage message;
  message.header = {{1700000000, 5}, "base"};
  message.chunk.fields = CommandField::kPosition;
  for (int k = 0; k <= kMaxChunkWaypoints; ++k) {
    message.chunk.waypoints.push_back({1700000001.0 + 0.01 * k, JointCommand::zero(7)});
  }
  const Sample<JointChunkMessage> got = roundTrip(message);
  EXPECT_NE(got.malformed.find("a chunk carries 1 to 64 waypoints, this one 65"), std::string::npos)
      << got.malformed;
  EXPECT_EQ(got.malformed_reason, Reason::kInvalidChunk);
  EXPECT_EQ(got.message.header.stamp, message.header.stamp);
}

TEST(TransportBounds, AStampPastInt32SecondsSaturatesInsteadOfWrapping) {
  constexpr std::int64_t kSecond = 1'000'000'000;
  // A time 1e9 s after 2025 (int32 seconds end in 2038).
  const Stamp ahead = Stamp::fromNanoseconds((std::int64_t{1'760'000'000} + kSecond) * kSecond);
  EXPECT_EQ(ahead.sec, std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(ahead.nanosec, 999'999'999U);
  const Stamp before = Stamp::fromNanoseconds(std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(before.sec, std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(before.nanosec, 0U);
  EXPECT_EQ(Stamp::fromSeconds(1e300).sec, std::numeric_limits<std::int32_t>::max());
  const Stamp now{1'760'000'000, 123};
  EXPECT_EQ(Stamp::fromNanoseconds(now.nanoseconds()), now);
  EXPECT_TRUE(Stamp::holds(1.76e9));
  EXPECT_FALSE(Stamp::holds(2.76e9));
  EXPECT_FALSE(Stamp::holds(std::numeric_limits<double>::quiet_NaN()));
}

}  // namespace
}  // namespace comply::transport
