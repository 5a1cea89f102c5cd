// The bytes on the wire, held against a vector derived by hand from the CDR rules, so that a
// ROS 2 node (rmw_cyclonedds, XCDR1) reads what comply writes. The message is sent through a
// real writer and reader on a loopback participant and taken serialised (dds_takecdr), so the
// bytes are exactly what CycloneDDS puts in the DATA submessage.

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <span>
#include <vector>

#include "committed_values.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/endpoints.hpp"
#include "comply_msgs/msg/JointCommand.h"
#include "loopback.hpp"
#include "message_values.hpp"

namespace comply::transport {
namespace {

/// Writes `message` and returns the serialised sample a reader receives (header included).
template <typename Message>
std::vector<std::uint8_t> wireBytes(const Message& message) {
  Loopback<Message> loopback("cdr_test");
  loopback.send(message);
  return takeSerialized(loopback.reader.handle());
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
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 88 reflex_force x = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 96 reflex_force y = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 104 reflex_force z = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 112 reflex_torque x = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 120 reflex_torque y = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 128 reflex_torque z = 0
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
  // count 4 + pad 4 + 56 each (64) -> 856; force_axes and wrench_target 12 doubles (96) -> 952;
  // reflex_force and reflex_torque 6 doubles (48) -> 1000; workspace_min and workspace_max 6
  // doubles (48) -> 1048. Body 1048, plus the 4-byte encapsulation header.
  ASSERT_EQ(bytes.size(), 1052U);
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

// comply's own CDR encoder (what a recording stores) against CycloneDDS's serialisation of the
// same message: byte for byte, for every message type, with every field away from its default
// and vectors of uneven lengths so that each alignment rule is exercised.

double value(std::mt19937& random) {
  return std::uniform_real_distribution<double>(-9, 9)(random);
}

/// What the host and its transport process hand each other decodes back to the same bytes, and
/// every cut of it short of its last field is refused.
template <typename Message>
void expectDecoderReadsTheWire(const std::vector<std::uint8_t>& wire) {
  Message decoded;
  ASSERT_TRUE(decodeCdr(wire, decoded));
  std::vector<std::uint8_t> again;
  encodeCdr(decoded, again);
  EXPECT_EQ(again, wire);
  if constexpr (requires { decoded.command.stamp_s; }) {
    EXPECT_EQ(decoded.command.stamp_s, decoded.header.stamp.seconds());
  }
  const std::size_t padding = wire[3] & 3U;
  for (std::size_t cut = 0; cut + padding < wire.size(); ++cut) {
    Message part;
    EXPECT_FALSE(decodeCdr(std::span(wire.data(), cut), part)) << cut << " of " << wire.size();
  }
}

template <typename Message>
void expectEncoderMatchesTheWire(const Message& message) {
  std::vector<std::uint8_t> encoded;
  encodeCdr(message, encoded);
  const std::vector<std::uint8_t> wire = wireBytes(message);
  ASSERT_EQ(encoded.size(), wire.size());
  EXPECT_EQ(encoded, wire);
  if constexpr (requires(Message decoded) { decodeCdr(wire, decoded); }) {
    expectDecoderReadsTheWire<Message>(wire);
  }
}

TEST(TransportCdrEncoder, CommandsMatchTheWire) {
  std::mt19937 random(7);
  CartesianCommandMessage cartesian;
  cartesian.header = {{12, 345}, "fr3_link0"};
  cartesian.command = CartesianCommand::zero(5);
  cartesian.command.fields = CommandField::kPosition | CommandField::kNullspace;
  cartesian.command.position = Eigen::Vector3d(0.1, -0.2, 0.3);
  cartesian.command.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  cartesian.command.stiffness_translational << 1, 2, 3, 2, 5, 6, 3, 6, 9;
  cartesian.command.damping_mode = DampingMode::kRatio;
  cartesian.command.damping_ratio << 0.7, 0.8, 0.9, 1.0, 1.1, 1.2;
  cartesian.command.task_frame = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
  for (int i = 0; i < 5; ++i) {
    cartesian.command.nullspace_position[i] = value(random);
    cartesian.command.torque_feedforward[i] = value(random);
  }
  expectEncoderMatchesTheWire(cartesian);

  JointCommandMessage joint;
  joint.header = {{-3, 999'999'999}, "odd"};
  joint.command = JointCommand::zero(3);
  joint.command.fields = CommandField::kStiffness;
  joint.command.stiffness << 10, 20, 30;
  joint.command.velocity.resize(0);
  expectEncoderMatchesTheWire(joint);
}

TEST(TransportCdrEncoder, ChunksMatchTheWire) {
  std::mt19937 random(11);
  CartesianChunkMessage cartesian;
  cartesian.header = {{100, 7}, "fr3_link0"};
  cartesian.chunk.fields = CommandField::kPosition | CommandField::kStiffness;
  for (int k = 0; k < 4; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{100.5 + 0.0667 * k, CartesianCommand::zero(6)};
    waypoint.command.position = Eigen::Vector3d(value(random), value(random), value(random));
    waypoint.command.stiffness_translational.diagonal() << value(random), 2, 3;
    waypoint.command.nullspace_position.setConstant(value(random));
    cartesian.chunk.waypoints.push_back(waypoint);
  }
  expectEncoderMatchesTheWire(cartesian);
  // The observation it was planned for and its takeover (at waypoint 2) travel as stamps; a chunk
  // that gives neither reads back NaN (all zero on the wire).
  cartesian.chunk.observation_s = 100.25;
  cartesian.chunk.takeover_s = cartesian.chunk.waypoints[2].time_s;
  expectEncoderMatchesTheWire(cartesian);
  std::vector<std::uint8_t> bytes;
  encodeCdr(cartesian, bytes);
  CartesianChunkMessage decoded;
  ASSERT_TRUE(decodeCdr(bytes, decoded));
  EXPECT_EQ(decoded.chunk.observation_s, 100.25);
  EXPECT_NEAR(decoded.chunk.takeover_s, cartesian.chunk.takeover_s, 1e-9);

  JointChunkMessage joint;
  joint.header = {{-1, 1}, ""};
  expectEncoderMatchesTheWire(joint);  // no waypoints
  joint.chunk.waypoints.push_back({3.5, JointCommand::zero(2)});
  joint.chunk.waypoints.front().command.velocity.resize(0);
  expectEncoderMatchesTheWire(joint);
  encodeCdr(joint, bytes);
  JointChunkMessage joint_decoded;
  ASSERT_TRUE(decodeCdr(bytes, joint_decoded));
  EXPECT_TRUE(std::isnan(joint_decoded.chunk.observation_s));
  EXPECT_TRUE(std::isnan(joint_decoded.chunk.takeover_s));
}

// Every table field set (message_values.hpp): sequences of 1 to 3 elements and strings of
// several lengths between them, so the encoder meets each alignment the fields can leave.
TEST(TransportCdrEncoder, StateDiagnosticsAndRequestsMatchTheWire) {
  ControllerStateMessage state;
  testing::DistinctValues{}.set(state);
  state.state = HostState::kFault;
  state.contact_wrench_source = WrenchSource::kSensor;
  expectEncoderMatchesTheWire(state);
  DiagnosticsMessage diagnostics;
  testing::DistinctValues{.next = 7}.set(diagnostics);
  ASSERT_FALSE(diagnostics.outcomes.empty());
  diagnostics.outcomes.front().reason = Reason::kPoseJump;
  diagnostics.outcomes.back().reason = Reason::kNone;
  expectEncoderMatchesTheWire(diagnostics);
  diagnostics.outcomes.clear();
  diagnostics.publisher.clear();
  expectEncoderMatchesTheWire(diagnostics);

  RequestMessage request;
  request.header = {{9, 10}, "client"};
  request.request = RequestType::kDeactivate;
  expectEncoderMatchesTheWire(request);
}

// The committed request and its answer, of either kind, with an unknown (NaN) entry, and a
// refusal, which carries no entry.
TEST(TransportCdrEncoder, CommittedRequestAndAnswersMatchTheWire) {
  expectEncoderMatchesTheWire(testing::someCommittedRequest());
  expectEncoderMatchesTheWire(testing::someCartesianAnswer(5));
  expectEncoderMatchesTheWire(testing::someJointAnswer(3));
  expectEncoderMatchesTheWire(testing::someJointAnswer(0));

  std::vector<std::uint8_t> bytes;
  encodeCdr(testing::someCartesianAnswer(kMaxChunkWaypoints), bytes);
  CommittedMessage decoded;
  ASSERT_TRUE(decodeCdr(bytes, decoded));
  EXPECT_EQ(decoded.cartesian.size(), static_cast<std::size_t>(kMaxChunkWaypoints));
  EXPECT_TRUE(std::isnan(decoded.cartesian.back().command.position.x()));
  // One entry more than a chunk's waypoints: not an answer a host writes.
  encodeCdr(testing::someCartesianAnswer(kMaxChunkWaypoints + 1), bytes);
  EXPECT_FALSE(decodeCdr(bytes, decoded));
}

// A recorded cycle (what an exporter reads back from a recording): the state, its timing and
// the command in force decode to what was encoded, byte for byte once encoded again; two
// commands in force are not a record a host writes.
TEST(TransportCdrDecoder, CycleRecordsRoundTripWithTheirCommandInForce) {
  CycleRecordMessage record;
  testing::DistinctValues{}.set(record.state);
  record.compute_time_s = 2.5e-6;
  record.start_lateness_s = -1.0e-6;
  record.cartesian_in_force.push_back(testing::someCartesianAnswer(2).cartesian.back());
  std::vector<std::uint8_t> bytes;
  encodeCdr(record, bytes);
  CycleRecordMessage decoded;
  ASSERT_TRUE(decodeCdr(bytes, decoded));
  EXPECT_EQ(decoded.compute_time_s, 2.5e-6);
  EXPECT_EQ(decoded.start_lateness_s, -1.0e-6);
  ASSERT_EQ(decoded.cartesian_in_force.size(), 1U);
  EXPECT_TRUE(decoded.joint_in_force.empty());
  EXPECT_EQ(decoded.state.joint_names, record.state.joint_names);
  std::vector<std::uint8_t> again;
  encodeCdr(decoded, again);
  EXPECT_EQ(again, bytes);

  record.cartesian_in_force.clear();
  record.joint_in_force.push_back(testing::someJointAnswer(1).joint.back());
  encodeCdr(record, bytes);
  ASSERT_TRUE(decodeCdr(bytes, decoded));
  EXPECT_TRUE(decoded.cartesian_in_force.empty());
  ASSERT_EQ(decoded.joint_in_force.size(), 1U);
  encodeCdr(decoded, again);
  EXPECT_EQ(again, bytes);

  record.joint_in_force.push_back(record.joint_in_force.back());
  encodeCdr(record, bytes);
  EXPECT_FALSE(decodeCdr(bytes, decoded));
}

TEST(TransportCdrDecoder, RefusesWhatEncodeCdrDoesNotWrite) {
  JointCommandMessage joint;
  joint.header = {{1, 2}, "x"};
  joint.command = JointCommand::zero(3);
  std::vector<std::uint8_t> bytes;
  encodeCdr(joint, bytes);
  JointCommandMessage decoded;
  ASSERT_TRUE(decodeCdr(bytes, decoded));
  EXPECT_EQ(decoded.command.position.size(), 3);

  std::vector<std::uint8_t> big_endian = bytes;
  big_endian[1] = 0x00;  // CDR_BE
  EXPECT_FALSE(decodeCdr(big_endian, decoded));

  // A joint vector longer than any controller's: the count is the first after the header and
  // the fields (4 + 8 + 4 + 2 for "x", aligned to 4, + 4).
  std::vector<std::uint8_t> long_vector = bytes;
  const std::uint32_t count = kMaxDof + 1;
  std::memcpy(long_vector.data() + 4 + 16 + 4, &count, sizeof(count));
  EXPECT_FALSE(decodeCdr(long_vector, decoded));

  // A string without its NUL.
  std::vector<std::uint8_t> unterminated = bytes;
  unterminated[4 + 8 + 4 + 1] = 'y';
  EXPECT_FALSE(decodeCdr(unterminated, decoded));

  // A count larger than the bytes left could hold is refused before anything is allocated.
  ControllerStateMessage state;
  encodeCdr(state, bytes);
  const std::uint32_t names = 0xFFFFFFF0U;
  std::memcpy(bytes.data() + 4 + 8 + 4 + 1 + 1 + 1 + 1 + 8, &names, sizeof(names));
  EXPECT_FALSE(decodeCdr(bytes, state));
}

TEST(TransportCdrEncoder, DefinitionsCarryTheirDependencies) {
  const std::string definition = ros2MessageDefinition("comply_msgs/msg/CycleRecord");
  // The type's own text first, then each type it uses once, after a separator line.
  EXPECT_TRUE(definition.starts_with("# comply_msgs/CycleRecord"));
  const std::string separator = std::string(80, '=') + "\nMSG: ";
  for (const char* dependency :
       {"comply_msgs/ControllerState", "std_msgs/Header", "builtin_interfaces/Time",
        "comply_msgs/CartesianCommand", "comply_msgs/JointCommand"}) {
    const std::size_t at = definition.find(separator + dependency + "\n");
    EXPECT_NE(at, std::string::npos) << dependency;
    EXPECT_EQ(definition.find(separator + dependency + "\n", at + 1), std::string::npos)
        << dependency << " twice";
  }
  const std::string chunk = ros2MessageDefinition("comply_msgs/msg/JointChunk");
  EXPECT_NE(chunk.find(separator + "comply_msgs/JointCommand\n"), std::string::npos);
  EXPECT_NE(chunk.find(separator + "builtin_interfaces/Time\n"), std::string::npos);
  EXPECT_EQ(ros2MessageDefinition("comply_msgs/Request").find("MSG: comply_msgs"),
            std::string::npos);
  EXPECT_THROW(ros2MessageDefinition("comply_msgs/msg/Nothing"), std::out_of_range);
}

}  // namespace
}  // namespace comply::transport
