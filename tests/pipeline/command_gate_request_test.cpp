// An operator request's outcome: settled with the commands' (kind kRequest, its stamp and sender),
// counted as no command, and never a hold on the command topics.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "comply/pipeline/command_gate.hpp"

namespace comply::pipeline {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

Offer commandFrom(std::uint64_t participant, std::int64_t stamp_ns, std::int64_t now_ns) {
  Offer offer;
  offer.stamp_ns = stamp_ns;
  offer.kind = CommandKind::kCartesian;
  offer.publisher = participant * 16;  // a writer of that process
  offer.participant = participant;
  offer.now_ns = now_ns;
  return offer;
}

/// A wrapper that accepts, as the first command it numbers.
Verdict accept(std::int64_t /*stamp_ns*/) {
  Verdict verdict;
  verdict.sequence = 1;
  return verdict;
}

TEST(CommandGateRequests, ARequestIsSettledAsNoCommandAndTakesNoTopics) {
  CommandGate gate({.kind = CommandKind::kCartesian, .publisher_timeout_s = 600.0});
  const SenderId reader{1, 2, 3};
  gate.settleRequest(5 * kSecond, reader, CommandReason::kNone, "");
  const auto settled = gate.takeOutcomes();
  ASSERT_EQ(settled.size(), 1U);
  EXPECT_EQ(settled[0].kind, CommandKind::kRequest);
  EXPECT_EQ(settled[0].stamp_ns, 5 * kSecond);
  EXPECT_EQ(settled[0].sender, reader);
  EXPECT_TRUE(settled[0].applied);
  EXPECT_EQ(settled[0].reason, CommandReason::kNone);
  EXPECT_GT(settled[0].applied_ns, 0);
  EXPECT_EQ(gate.publisher(), 0U) << "a request took the command topics";
  const GateCounts counts = gate.counts();
  EXPECT_EQ(counts.received + counts.applied + counts.rejected, 0U) << "counted as a command";

  // The first command then takes the topics, whoever sent requests before it.
  EXPECT_EQ(gate.offer(commandFrom(7, 6 * kSecond, 1), true, accept), CommandReason::kNone);
  EXPECT_EQ(gate.publisher(), 7U * 16);
}

TEST(CommandGateRequests, ARefusedRequestCarriesItsReasonAndWhy) {
  CommandGate gate({.kind = CommandKind::kCartesian, .publisher_timeout_s = 600.0});
  ASSERT_EQ(gate.offer(commandFrom(7, 6 * kSecond, 1), true, accept), CommandReason::kNone);
  (void)gate.takeOutcomes();
  std::string why;
  ASSERT_FALSE(gate.admitRequest(/*participant=*/9, 2, why));
  gate.settleRequest(7 * kSecond, SenderId{9}, CommandReason::kOtherPublisher, why);
  gate.settleRequest(8 * kSecond, SenderId{7}, CommandReason::kNone, "tare: no sensor reading");
  const auto settled = gate.takeOutcomes();
  ASSERT_EQ(settled.size(), 2U);
  EXPECT_FALSE(settled[0].applied);
  EXPECT_EQ(settled[0].reason, CommandReason::kOtherPublisher);
  EXPECT_EQ(settled[0].message, why);
  EXPECT_EQ(settled[0].applied_ns, 0);
  EXPECT_FALSE(settled[1].applied) << "a request the host could not carry out";
  EXPECT_EQ(settled[1].reason, CommandReason::kNone);
  EXPECT_EQ(settled[1].message, "tare: no sensor reading");
  EXPECT_EQ(gate.counts().rejected, 0U);
}

}  // namespace
}  // namespace comply::pipeline
