// A field added to a copy of ControllerState's table (message_tables.hpp) and every spelling
// following it with no other change: the C++ struct, the .msg and IDL text, CDR both ways (after
// every old field: a reader of the old table still reads a top-level message, though not one
// nested in a sequence, as an outcome in Diagnostics.outcomes is), the DDS structs idlc
// generates, JSON, and the copy into ROS 2's generated type. Python's dict is the same visit()
// (python/src/py_convert.cpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "cdr_fields.hpp"
#include "comply/transport/cdr.hpp"
#include "comply/transport/message_copy.hpp"
#include "comply/transport/message_json.hpp"
#include "comply/transport/message_text.hpp"
#include "ros_like_messages.hpp"
#include "wire_fields.hpp"

namespace comply::transport {
namespace {

// clang-format off
#define GROWN_STATE_FIELDS(X) \
  COMPLY_CONTROLLER_STATE_FIELDS(X) \
  X(double, grip_force_n, grip_force, 0.0, "[N] the gripper's measured force")
// clang-format on

struct GrownState {
  COMPLY_MESSAGE_BODY(GROWN_STATE_FIELDS)
};

/// What idlc would generate from the grown IDL: the old struct and the new member.
struct GrownWireState : comply_msgs_msg_dds__ControllerState_ {
  double grip_force = 0.0;
};

GrownState someState() {
  GrownState state;
  state.header = {{1700000000, 250}, "fr3_link0"};
  state.state = HostState::kActive;
  state.joint_names = {"j1", "j2"};
  state.position = {0.1, -0.2};
  state.tank_energy_j = 0.75;
  state.grip_force_n = 12.5;
  return state;
}

TEST(MessageTables, AFieldAddedToATableIsInTheStructAndTheInterfaceFiles) {
  EXPECT_EQ(GrownState{}.grip_force_n, 0.0);
  const MessageText message{"ControllerState", "a grown state", {}, fieldTexts<GrownState>()};
  const std::string msg = rosMessageText(message);
  EXPECT_NE(
      msg.find("float64 contact_speed_brake  # [N] the contact-speed limit's braking force against "
               "the TCP's motion this cycle (0: none)\nfloat64 grip_force  # [N] the gripper's "
               "measured force\n"),
      std::string::npos)
      << msg;
  const std::string idl = ddsIdlText(message);
  EXPECT_NE(idl.find("  double contact_speed_brake;\n  double grip_force;\n};"), std::string::npos)
      << idl;
  // The rest is the table's own: the committed file's fields come first, unchanged.
  const std::string committed = ddsIdlText(hostMessageText("ControllerState"));
  EXPECT_EQ(idl.substr(idl.find("struct ControllerState_")).size(),
            committed.substr(committed.find("struct ControllerState_")).size() +
                std::string("  double grip_force;\n").size());
}

TEST(MessageTables, AFieldAddedToATableTravelsInCdrAfterTheOldOnes) {
  const GrownState sent = someState();
  std::vector<std::uint8_t> bytes;
  {
    cdr::Writer w(bytes);
    cdr::putFields(w, sent);
    w.finish();
  }
  GrownState received;
  cdr::Reader r(bytes);
  cdr::getFields(r, received);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(received.grip_force_n, 12.5);
  EXPECT_EQ(received.joint_names, sent.joint_names);
  EXPECT_EQ(received.tank_energy_j, 0.75);

  // An old reader (the committed table) reads every old field of the grown message.
  ControllerStateMessage old;
  cdr::Reader prefix(bytes);
  cdr::getFields(prefix, old);
  ASSERT_TRUE(prefix.ok());
  EXPECT_EQ(old.header.frame_id, "fr3_link0");
  EXPECT_EQ(old.position, sent.position);
  EXPECT_EQ(old.gain_fraction, 1.0);
  // The grown bytes are the old message's (without its end padding), then the new field: a
  // double, aligned to 8 from the start of the data.
  std::vector<std::uint8_t> old_bytes;
  encodeCdr(old, old_bytes);
  const std::size_t old_end = old_bytes.size() - old_bytes[3];  // byte 3: the padding added
  ASSERT_GT(bytes.size(), old_end);
  EXPECT_TRUE(std::equal(old_bytes.begin() + 4, old_bytes.begin() + old_end, bytes.begin() + 4));
  const std::size_t field_at = 4 + (old_end - 4 + 7) / 8 * 8;
  EXPECT_EQ(bytes.size(), field_at + 8);
  double grip_force_n = 0.0;
  std::memcpy(&grip_force_n, bytes.data() + field_at, sizeof(grip_force_n));
  EXPECT_EQ(grip_force_n, 12.5);
}

TEST(MessageTables, AFieldAddedToATableReachesTheDdsStructs) {
  using wire::fromWire;
  using wire::toWire;
  const GrownState sent = someState();
  GrownWireState wire_state{};
  wire::Borrowed borrowed;  // what the wire form points into, alive to the end
  {
    // What COMPLY_TO_WIRE reads and writes.
    const GrownState& message = sent;
    GrownWireState& out = wire_state;
    GROWN_STATE_FIELDS(COMPLY_TO_WIRE)
    EXPECT_EQ(out.grip_force, 12.5);
    EXPECT_EQ(out.joint_names._length, 2U);
    EXPECT_STREQ(out.joint_names._buffer[1], "j2");
    EXPECT_EQ(out.state, 1);
  }
  GrownState back;
  {
    // What COMPLY_FROM_WIRE reads and writes.
    const GrownWireState& in = wire_state;
    GrownState& message = back;
    GROWN_STATE_FIELDS(COMPLY_FROM_WIRE)
  }
  EXPECT_EQ(back.grip_force_n, 12.5);
  EXPECT_EQ(back.joint_names, sent.joint_names);
  EXPECT_EQ(back.header.stamp, sent.header.stamp);
  EXPECT_EQ(back.state, HostState::kActive);
}

TEST(MessageTables, AFieldAddedToATableIsInTheJson) {
  const nlohmann::json json = messageJson(someState());
  EXPECT_EQ(json.at("grip_force"), 12.5);
  EXPECT_EQ(json.at("state"), "active");
  EXPECT_EQ(json.at("tank_energy"), 0.75);
  EXPECT_EQ(json.at("header").at("stamp").at("nanosec"), 250);
  EXPECT_EQ(json.size(), messageJson(ControllerStateMessage{}).size() + 1);
}

COMPLY_MESSAGE_COPY(GrownState, GROWN_STATE_FIELDS)

/// What rosidl would generate from the grown .msg.
struct GrownRosState {
  GROWN_STATE_FIELDS(COMPLY_ROS_LIKE_MEMBER)
};

TEST(MessageTables, AFieldAddedToATableReachesTheRos2Message) {
  GrownRosState copy;
  copyMessage(someState(), copy);
  EXPECT_EQ(copy.grip_force, 12.5);
  EXPECT_EQ(copy.tank_energy, 0.75);
  EXPECT_EQ(copy.position, (std::vector<double>{0.1, -0.2}));
  EXPECT_EQ(copy.state, static_cast<std::uint8_t>(HostState::kActive));
}

}  // namespace
}  // namespace comply::transport
