// The committed request and its answer on every way a host's messages travel: DDS (a round trip of
// each, a request's frame_id over its bound and an answer longer than a chunk refused where they
// are read), the frames between a host and its transport process, and the in-process bus. Each
// arrives as it was sent: its CDR bytes are the sent message's.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "committed_values.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/endpoints.hpp"
#include "comply/transport/in_process.hpp"
#include "frame_adapter.hpp"
#include "frames.hpp"
#include "loopback.hpp"

namespace comply::transport {
namespace {

template <typename Message>
Sample<Message> roundTrip(const Message& message) {
  Loopback<Message> loopback("committed");
  loopback.send(message);
  std::vector<Sample<Message>> samples;
  EXPECT_EQ(loopback.reader.take(samples), 1U);
  return samples.empty() ? Sample<Message>{} : samples.front();
}

template <typename Message>
std::vector<std::uint8_t> cdrOf(const Message& message) {
  std::vector<std::uint8_t> bytes;
  encodeCdr(message, bytes);
  return bytes;
}

TEST(TransportCommitted, TopicsAreNamedAndReliable) {
  EXPECT_EQ(topicName("arm", Topic::kCommittedRequest), "rt/arm/committed_request");
  EXPECT_EQ(topicName("arm", Topic::kCommitted), "rt/arm/committed");
  for (const Topic topic : {Topic::kCommittedRequest, Topic::kCommitted}) {
    EXPECT_TRUE(qosOf(topic).reliable);
    EXPECT_EQ(qosOf(topic).depth, 10);
  }
}

TEST(TransportCommitted, TheRequestRoundTripsThroughDds) {
  CommittedRequestMessage request = testing::someCommittedRequest();
  const Sample<CommittedRequestMessage> got = roundTrip(request);
  EXPECT_TRUE(got.malformed.empty()) << got.malformed;
  EXPECT_EQ(cdrOf(got.message), cdrOf(request));
  EXPECT_EQ(got.message.dt_s, 1.0 / 30.0);
  EXPECT_NE(got.sender, Gid{}) << "the answer names its sender";

  // A frame_id over its bound: refused where it is read (the host answers why), the text not kept.
  request.header.frame_id = std::string(300, 'x');
  const Sample<CommittedRequestMessage> refused = roundTrip(request);
  EXPECT_NE(refused.malformed.find("header.frame_id is 300 bytes"), std::string::npos)
      << refused.malformed;
  EXPECT_EQ(refused.malformed_reason, Reason::kTooLarge);
  EXPECT_TRUE(refused.message.header.frame_id.empty());
  EXPECT_EQ(refused.message.header.stamp, request.header.stamp);
}

TEST(TransportCommitted, TheAnswersRoundTripThroughDds) {
  for (const CommittedMessage& answer :
       {testing::someCartesianAnswer(5), testing::someJointAnswer(3),
        testing::someJointAnswer(0)}) {
    const Sample<CommittedMessage> got = roundTrip(answer);
    EXPECT_TRUE(got.malformed.empty()) << got.malformed;
    EXPECT_EQ(cdrOf(got.message), cdrOf(answer));
    EXPECT_EQ(got.message.message, answer.message);
  }
  const Sample<CommittedMessage> longer = roundTrip(testing::someCartesianAnswer(65));
  EXPECT_NE(longer.malformed.find("cartesian has 65 entries, more than an answer holds (64)"),
            std::string::npos)
      << longer.malformed;
}

TEST(TransportCommitted, BothCrossTheTransportProcesssFrames) {
  using process::FrameKind;
  // The process hands the host a request as a sample of the inbox's last topic.
  Sample<CommittedRequestMessage> sample;
  sample.message = testing::someCommittedRequest();
  sample.publisher = 0x1122334455667788ULL;
  sample.participant = 42;
  sample.sender = testing::someCartesianAnswer(0).sender;
  std::vector<std::uint8_t> scratch;
  std::vector<std::uint8_t> stream;
  process::appendSampleFrame(process::sampleFrameKind(5), sample, scratch, stream);
  EXPECT_EQ(process::sampleFrameKind(5), FrameKind::kCommittedRequest);
  process::IncomingFrames incoming;
  incoming.append(stream);
  Inbox inbox;
  EXPECT_EQ(incoming.handleNext(inbox), FrameKind::kCommittedRequest);
  EXPECT_FALSE(incoming.broken());
  ASSERT_EQ(inbox.committed_requests.size(), 1U);
  const Sample<CommittedRequestMessage>& taken = inbox.committed_requests[0];
  EXPECT_EQ(taken.publisher, sample.publisher);
  EXPECT_EQ(taken.participant, sample.participant);
  EXPECT_EQ(taken.sender, sample.sender);
  EXPECT_EQ(cdrOf(taken.message), cdrOf(sample.message));

  // The host hands the process its answer to publish.
  const CommittedMessage answer = testing::someCartesianAnswer(16);
  process::OutgoingFrames outgoing;
  process::FrameReader reader;
  reader.append(outgoing.encode(FrameKind::kCommitted, answer));
  const std::optional<process::Frame> frame = reader.next();
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->kind, FrameKind::kCommitted);
  CommittedMessage decoded;
  ASSERT_TRUE(decodeCdr(frame->payload, decoded));
  EXPECT_EQ(cdrOf(decoded), cdrOf(answer));
}

TEST(TransportCommitted, BothCrossTheInProcessBus) {
  const std::shared_ptr<InProcessBus> bus = InProcessBus::named("committed_bus");
  const std::unique_ptr<HostTransport> host = makeInProcessHostTransport({.name = "committed_bus"});
  const CommittedRequestMessage request = testing::someCommittedRequest();
  bus->send(request, 7);
  Inbox inbox;
  host->receive(inbox, 1.0);
  ASSERT_EQ(inbox.committed_requests.size(), 1U);
  Gid seven{};
  const std::uint64_t publisher = 7;
  std::memcpy(seven.data(), &publisher, sizeof(publisher));
  EXPECT_EQ(inbox.committed_requests[0].sender, seven);
  EXPECT_EQ(cdrOf(inbox.committed_requests[0].message), cdrOf(request));

  const CommittedMessage answer = testing::someJointAnswer(4);
  host->publish(answer);
  std::optional<CommittedMessage> got;
  EXPECT_TRUE(bus->waitForCommitted(1.0, [&](const CommittedMessage& message) {
    got = message;
    return true;
  }));
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(cdrOf(*got), cdrOf(answer));
  EXPECT_TRUE(answers(*got, answer.request_stamp, Gid{}));
  EXPECT_FALSE(answers(*got, Stamp{1, 2}, Gid{}));
}

}  // namespace
}  // namespace comply::transport
