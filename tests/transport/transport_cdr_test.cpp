// The bytes on the wire, held against a vector derived by hand from the CDR rules, so that a
// ROS 2 node (rmw_cyclonedds, XCDR1) reads what comply writes. The message is sent through a
// real writer and reader on a loopback participant and taken serialised (dds_takecdr), so the
// bytes are exactly what CycloneDDS puts in the DATA submessage.

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "comply/transport/endpoints.hpp"
#include "comply_msgs/msg/JointCommand.h"
#include "loopback.hpp"

namespace comply::transport {
namespace {

/// Writes `message` and returns the serialised sample a reader receives (header included).
template <typename Message>
std::vector<std::uint8_t> wireBytes(const Message& message) {
  Loopback<Message> loopback("cdr_test");
  loopback.send(message);
  ddsi_serdata* serdata = nullptr;
  dds_sample_info_t info;
  const dds_return_t count =
      dds_takecdr(loopback.reader.handle(), &serdata, 1, &info, DDS_ANY_STATE);
  EXPECT_EQ(count, 1);
  if (count != 1) {
    return {};
  }
  std::vector<std::uint8_t> bytes(ddsi_serdata_size(serdata));
  ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
  ddsi_serdata_unref(serdata);
  return bytes;
}

TEST(TransportCdr, JointCommandBytesFollowTheCdrRules) {
  JointCommandMessage message;
  message.header.stamp = {1, 2};
  message.header.frame_id = "base";
  message.command.fields = CommandField::kPosition | CommandField::kStiffness;  // 1 | 8
  message.command.position = JointVector::Zero(2);
  message.command.position << 1.5, -0.25;
  message.command.stiffness = JointVector::Zero(2);
  message.command.stiffness << 100.0, 200.0;

  // Offsets count from the first byte after the 4-byte encapsulation header; every primitive is
  // aligned to its size (doubles to 8: XCDR1); a string is a uint32 length including the NUL,
  // then its bytes; a sequence is a uint32 count, then its elements; an empty sequence is only
  // the count.
  const std::vector<std::uint8_t> expected = {
      0x00, 0x01, 0x00, 0x00,                          // CDR_LE, options 0
      0x01, 0x00, 0x00, 0x00,                          //  0 header.stamp.sec = 1
      0x02, 0x00, 0x00, 0x00,                          //  4 header.stamp.nanosec = 2
      0x05, 0x00, 0x00, 0x00,                          //  8 frame_id length 5 ("base" + NUL)
      'b',  'a',  's',  'e',  0x00,                    // 12 frame_id
      0x00, 0x00, 0x00,                                // 17 padding to 4
      0x09, 0x00, 0x00, 0x00,                          // 20 fields = position | stiffness
      0x02, 0x00, 0x00, 0x00,                          // 24 position: 2 entries
      0x00, 0x00, 0x00, 0x00,                          // 28 padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF8, 0x3F,  // 32 1.5    = 0x3FF8000000000000
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xD0, 0xBF,  // 40 -0.25  = 0xBFD0000000000000
      0x00, 0x00, 0x00, 0x00,                          // 48 velocity: 0 entries
      0x00, 0x00, 0x00, 0x00,                          // 52 acceleration: 0 entries
      0x02, 0x00, 0x00, 0x00,                          // 56 stiffness: 2 entries
      0x00, 0x00, 0x00, 0x00,                          // 60 padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x59, 0x40,  // 64 100.0  = 0x4059000000000000
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x69, 0x40,  // 72 200.0  = 0x4069000000000000
      0x00, 0x00, 0x00, 0x00,                          // 80 damping: 0 entries
      0x00, 0x00, 0x00, 0x00,                          // 84 torque_feedforward: 0 entries
  };
  EXPECT_EQ(wireBytes(message), expected);
}

TEST(TransportCdr, CartesianCommandSizeFollowsTheTable) {
  CartesianCommandMessage message;
  message.header.frame_id = "";  // length 1 (the NUL)
  message.command = CartesianCommand::zero(7);
  const std::vector<std::uint8_t> bytes = wireBytes(message);
  // 4 header + stamp 8 + string 4 + 1 -> 17, pad to 20, fields 4 -> 24; then 3 + 4 + 6 + 6 + 9 *
  // 4 doubles (55 doubles, 440 bytes) -> 464; damping_mode octet -> 465, pad to 472 for
  // damping_ratio 6 + task_frame 4 + wrench 6 doubles (128) -> 600; four sequences of 7 doubles:
  // count 4 + pad 4 + 56 each (64) -> 856. Body 856, plus the 4-byte encapsulation header.
  ASSERT_EQ(bytes.size(), 860U);
  EXPECT_EQ(bytes[1], 0x01);        // CDR_LE
  EXPECT_EQ(bytes[4 + 464], 0x00);  // damping_mode absolute
  EXPECT_EQ(bytes[4 + 600], 7);     // torque_feedforward count
}

TEST(TransportCdr, OversizedJointVectorIsReportedNotTruncated) {
  Participant participant({.domain_id = testDomain()});
  Writer<JointCommandMessage> writer(participant, "cdr_test");
  Reader<JointCommandMessage> reader(participant, "cdr_test");
  ASSERT_TRUE(writer.waitForMatch(1, 5.0));
  // More entries than any JointVector holds: only a foreign writer can send this.
  std::vector<double> many(kMaxDof + 3, 1.0);
  comply_msgs_msg_dds__JointCommand_ raw{};
  raw.header.frame_id = const_cast<char*>("");
  raw.fields = 1;
  raw.position._maximum = raw.position._length = static_cast<std::uint32_t>(many.size());
  raw.position._buffer = many.data();
  ASSERT_GE(dds_write(writer.handle(), &raw), 0);
  ASSERT_TRUE(reader.wait(5.0));
  std::vector<Sample<JointCommandMessage>> samples;
  ASSERT_EQ(reader.take(samples), 1U);
  EXPECT_NE(samples[0].malformed.find("position has 15 entries"), std::string::npos)
      << samples[0].malformed;
}

}  // namespace
}  // namespace comply::transport
