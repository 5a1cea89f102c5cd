// copyMessage() (message_copy.hpp): every field of the host's messages reaches a struct shaped as
// ROS 2's generated comply_msgs, under its wire name and with its value, nested outcomes included.

#include "comply/transport/message_copy.hpp"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

#include "message_values.hpp"
#include "ros_like_messages.hpp"

namespace comply::transport::testing {

// The ROS 2 side read by its wire names, in table order as flatten() reads the host's messages.
#define BY_WIRE_NAME(Type, member, wire, init, doc) flatten(message.wire, flat);
void flatten(const ros_like::ChunkTiming& message, Flat& flat) {
  COMPLY_CHUNK_TIMING_FIELDS(BY_WIRE_NAME)
}
void flatten(const ros_like::CommandOutcome& message, Flat& flat) {
  COMPLY_COMMAND_OUTCOME_FIELDS(BY_WIRE_NAME)
}
void flatten(const ros_like::ControllerState& message, Flat& flat) {
  COMPLY_CONTROLLER_STATE_FIELDS(BY_WIRE_NAME)
}
void flatten(const ros_like::Diagnostics& message, Flat& flat) {
  COMPLY_DIAGNOSTICS_FIELDS(BY_WIRE_NAME)
}
#undef BY_WIRE_NAME

namespace {
template <typename RosMessage, typename Message>
void expectEveryFieldCopied(const Message& message) {
  RosMessage copy;
  copyMessage(message, copy);
  const Flat host = flat(message);
  const Flat ros = flat(copy);
  EXPECT_EQ(host.numbers, ros.numbers);
  EXPECT_EQ(host.texts, ros.texts);
}

TEST(MessageCopy, EveryStateFieldReachesItsWireName) {
  ControllerStateMessage state;
  DistinctValues{}.set(state);
  expectEveryFieldCopied<ros_like::ControllerState>(state);
  // The fields whose C++ name is not their wire name, and the conversions, by name.
  ros_like::ControllerState copy;
  copyMessage(state, copy);
  EXPECT_NE(state.tank_energy_j, 0.0);
  EXPECT_EQ(copy.tank_energy, state.tank_energy_j);
  EXPECT_EQ(copy.contact_wrench_bandwidth, state.contact_wrench_bandwidth_hz);
  EXPECT_EQ(copy.contact_wrench_source, static_cast<std::uint8_t>(state.contact_wrench_source));
  EXPECT_EQ(copy.contact_wrench_task, state.contact_wrench_task);
  EXPECT_EQ(copy.reference_stamp.nanosec, state.reference_stamp.nanosec);
  EXPECT_EQ(copy.header.frame_id, state.header.frame_id);
  EXPECT_TRUE(copy.passivity);
}

TEST(MessageCopy, DiagnosticsCarryTheirOutcomes) {
  DiagnosticsMessage diagnostics;
  DistinctValues{}.set(diagnostics);
  ASSERT_FALSE(diagnostics.outcomes.empty());
  expectEveryFieldCopied<ros_like::Diagnostics>(diagnostics);
  ros_like::Diagnostics copy;
  copyMessage(diagnostics, copy);
  ASSERT_EQ(copy.outcomes.size(), diagnostics.outcomes.size());
  EXPECT_EQ(copy.outcomes.back().sender, diagnostics.outcomes.back().sender);
  EXPECT_EQ(copy.outcomes.back().message, diagnostics.outcomes.back().message);
  EXPECT_EQ(copy.period, diagnostics.period_s);
}

TEST(MessageCopy, ACopyReplacesTheSequencesOfAnEarlierOne) {
  DiagnosticsMessage diagnostics;
  DistinctValues{}.set(diagnostics);
  ros_like::Diagnostics copy;
  copyMessage(diagnostics, copy);
  diagnostics.outcomes.clear();
  diagnostics.rejections = {7};
  copyMessage(diagnostics, copy);
  EXPECT_TRUE(copy.outcomes.empty());
  EXPECT_EQ(copy.rejections, std::vector<std::uint64_t>{7});
}

}  // namespace
}  // namespace comply::transport::testing
