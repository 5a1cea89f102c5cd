// The interface files agree with each other and with the schema: the command IDLs are what
// `comply schema --format idl` prints now, and every IDL struct has the members of its .msg in
// the same order with the types rosidl maps them to. Then every message survives a round trip
// through a writer and a reader on a loopback participant.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "comply/schema/describe.hpp"
#include "comply/transport/endpoints.hpp"
#include "comply/transport/message_text.hpp"
#include "loopback.hpp"
#include "message_values.hpp"
#include "text_file.hpp"

namespace comply::transport {
namespace {

const std::filesystem::path kSourceDir = COMPLY_SOURCE_DIR;
const std::filesystem::path kIdlDir = kSourceDir / "src" / "transport" / "idl";

std::string contents(const std::filesystem::path& file) {
  return comply::testing::textOf(file);
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

/// rosidl's DDS spelling of a .msg type (IDL keyword or module path).
std::string idlType(const std::string& msg_type) {
  static const std::map<std::string, std::string> kTypes = {
      {"bool", "boolean"},
      {"float64", "double"},
      {"uint8", "octet"},
      {"uint32", "unsigned long"},
      {"uint64", "unsigned long long"},
      {"int32", "long"},
      {"string", "string"},
      {"std_msgs/Header", "std_msgs::msg::dds_::Header_"},
      {"builtin_interfaces/Time", "builtin_interfaces::msg::dds_::Time_"}};
  const auto known = kTypes.find(msg_type);
  if (known != kTypes.end()) {
    return known->second;
  }
  const std::string package = "comply_msgs/";
  const std::string name =
      msg_type.starts_with(package) ? msg_type.substr(package.size()) : msg_type;
  return "comply_msgs::msg::dds_::" + name + "_";
}

/// The members of a .msg file as IDL declarations ("double position[3]").
std::vector<std::string> msgMembers(const std::filesystem::path& file) {
  std::vector<std::string> members;
  std::istringstream lines(contents(file));
  const std::regex member(R"(([A-Za-z0-9_/]+)(\[(<=)?(\d*)\])?\s+([a-z0-9_]+))");
  for (std::string line; std::getline(lines, line);) {
    line = trim(line.substr(0, line.find('#')));
    std::smatch match;
    if (line.empty() ||
        (line.find('=') != std::string::npos && line.find("<=") == std::string::npos)) {
      continue;  // a constant: not on the wire (a bound, T[<=N], is not one)
    }
    EXPECT_TRUE(std::regex_match(line, match, member)) << file << ": " << line;
    const std::string type = idlType(match[1]);
    const std::string name = match[5].str();
    if (!match[2].matched) {
      members.push_back(type + " " + name);
    } else if (match[3].matched) {  // bounded: T[<=N]
      members.push_back("sequence<" + type + ", " + match[4].str() + "> " + name);
    } else if (match[4].length() == 0) {
      members.push_back("sequence<" + type + "> " + name);
    } else {
      members.push_back(type + " " + name + "[" + match[4].str() + "]");
    }
  }
  return members;
}

/// The members of `struct <name>_` in an IDL file.
std::vector<std::string> idlMembers(const std::filesystem::path& file, const std::string& name) {
  const std::string text = contents(file);
  const auto start = text.find("struct " + name + "_ {");
  EXPECT_NE(start, std::string::npos) << file << " has no struct " << name << "_";
  std::vector<std::string> members;
  std::istringstream lines(text.substr(start, text.find("};", start) - start));
  std::string line;
  std::getline(lines, line);  // struct ... {
  while (std::getline(lines, line)) {
    line = trim(line);
    if (!line.empty()) {
      members.push_back(line.substr(0, line.find(';')));
    }
  }
  return members;
}

TEST(TransportMessages, CommandIdlIsGeneratedFromTheSchema) {
  EXPECT_EQ(contents(kIdlDir / "comply_msgs" / "msg" / "CartesianCommand.idl"),
            schema::ddsIdl(schema::CommandKind::kCartesian))
      << "regenerate with: comply schema --format idl --kind cartesian";
  EXPECT_EQ(contents(kIdlDir / "comply_msgs" / "msg" / "JointCommand.idl"),
            schema::ddsIdl(schema::CommandKind::kJoint))
      << "regenerate with: comply schema --format idl --kind joint";
}

TEST(TransportMessages, HostMessagesAreGeneratedFromTheirTables) {
  for (const std::string_view name : hostMessageNames()) {
    const MessageText message = hostMessageText(name);
    const std::string file(name);
    EXPECT_EQ(contents(kSourceDir / "msg" / (file + ".msg")), rosMessageText(message))
        << "regenerate with: make generated";
    EXPECT_EQ(contents(kIdlDir / "comply_msgs" / "msg" / (file + ".idl")), ddsIdlText(message))
        << "regenerate with: make generated";
  }
}

TEST(TransportMessages, EveryIdlStructMatchesItsMsg) {
  for (const std::string name : {"CartesianCommand", "JointCommand", "CartesianChunk", "JointChunk",
                                 "ControllerState", "CommandOutcome", "ChunkTiming", "Diagnostics",
                                 "Request", "CommittedRequest", "Committed"}) {
    const std::vector<std::string> msg = msgMembers(kSourceDir / "msg" / (name + ".msg"));
    const std::vector<std::string> idl =
        idlMembers(kIdlDir / "comply_msgs" / "msg" / (name + ".idl"), name);
    EXPECT_GE(msg.size(), 2U) << name;
    EXPECT_EQ(msg, idl) << name << ".msg and " << name << ".idl disagree";
  }
}

TEST(TransportMessages, TopicNamesAndQosAreRos2s) {
  EXPECT_EQ(topicName("comply", Topic::kCartesianCommand), "rt/comply/cartesian_command");
  EXPECT_EQ(topicName("arm2", Topic::kState), "rt/arm2/state");
  EXPECT_TRUE(qosOf(Topic::kJointCommand).reliable);
  EXPECT_EQ(qosOf(Topic::kJointCommand).depth, 10);
  EXPECT_FALSE(qosOf(Topic::kState).reliable);
  EXPECT_EQ(qosOf(Topic::kState).depth, 5);
  EXPECT_NE(cycloneConfig({}).find("127.0.0.1"), std::string::npos);
  EXPECT_NE(cycloneConfig({}).find("<AllowMulticast>false"), std::string::npos);
  EXPECT_TRUE(cycloneConfig({.network = Network::kAll}).empty());
}

template <typename Message>
Sample<Message> roundTrip(const Message& message) {
  Loopback<Message> loopback("round_trip");
  loopback.send(message);
  std::vector<Sample<Message>> samples;
  EXPECT_EQ(loopback.reader.take(samples), 1U);
  return samples.empty() ? Sample<Message>{} : samples.front();
}

TEST(TransportMessages, CartesianCommandRoundTrip) {
  CartesianCommandMessage message;
  message.header = {{1700000000, 123456789}, "base"};
  message.command = CartesianCommand::zero(7);
  message.command.fields = CommandField::kPosition | CommandField::kNullspace;
  message.command.position = {0.4, -0.1, 0.5};
  message.command.orientation = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
  message.command.stiffness_translational(0, 1) = 3.0;  // row-major on the wire
  message.command.damping_mode = DampingMode::kRatio;
  message.command.nullspace_position.setLinSpaced(7, 0.1, 0.7);
  const Sample<CartesianCommandMessage> got = roundTrip(message);
  EXPECT_TRUE(got.malformed.empty());
  EXPECT_EQ(got.message.header.stamp, message.header.stamp);
  EXPECT_EQ(got.message.header.frame_id, "base");
  EXPECT_DOUBLE_EQ(got.message.command.stamp_s, 1700000000.123456789);
  EXPECT_EQ(got.message.command.fields, message.command.fields);
  EXPECT_EQ(got.message.command.position, message.command.position);
  EXPECT_EQ(got.message.command.orientation.coeffs(), message.command.orientation.coeffs());
  EXPECT_EQ(got.message.command.stiffness_translational(0, 1), 3.0);
  EXPECT_EQ(got.message.command.stiffness_translational(1, 0), 0.0);
  EXPECT_EQ(got.message.command.damping_mode, DampingMode::kRatio);
  EXPECT_EQ(got.message.command.nullspace_position, message.command.nullspace_position);
  EXPECT_NE(got.publisher, 0U);
}

TEST(TransportMessages, ChunkRoundTripCarriesEachWaypointsTime) {
  JointChunkMessage message;
  message.header = {{1700000000, 5}, "base"};
  message.chunk.fields = CommandField::kPosition | CommandField::kStiffness;
  for (int k = 0; k < 3; ++k) {
    ChunkWaypoint<JointCommand> waypoint{1700000000.25 + 0.1 * k, JointCommand::zero(7)};
    waypoint.command.position.setConstant(0.1 * k);
    waypoint.command.stiffness.setConstant(100.0 + k);
    message.chunk.waypoints.push_back(waypoint);
  }
  const Sample<JointChunkMessage> got = roundTrip(message);
  EXPECT_TRUE(got.malformed.empty()) << got.malformed;
  EXPECT_EQ(got.message.header.stamp, message.header.stamp);
  EXPECT_DOUBLE_EQ(got.message.chunk.stamp_s, message.header.stamp.seconds());
  EXPECT_EQ(got.message.chunk.fields, message.chunk.fields);
  ASSERT_EQ(got.message.chunk.waypoints.size(), 3U);
  for (int k = 0; k < 3; ++k) {
    const auto& waypoint = got.message.chunk.waypoints[static_cast<std::size_t>(k)];
    // Times travel as stamps, to the nanosecond; a double of seconds since the epoch holds them to
    // 0.24 us.
    EXPECT_NEAR(waypoint.time_s, message.chunk.waypoints[static_cast<std::size_t>(k)].time_s, 5e-7);
    EXPECT_EQ(waypoint.command.position,
              message.chunk.waypoints[static_cast<std::size_t>(k)].command.position);
    EXPECT_EQ(waypoint.command.stiffness[6], 100.0 + k);
  }
}

// Every field of the tables away from its default, each value distinct, so a field lost or
// swapped on the way shows; a field added to a table is covered with no line here.
template <typename Message, typename Tweak>
void expectEveryFieldRoundTrips(Tweak&& tweak) {
  Message message;
  testing::DistinctValues{}.set(message);
  tweak(message);
  const testing::Flat sent = testing::flat(message);
  const testing::Flat got = testing::flat(roundTrip(message).message);
  EXPECT_EQ(got.numbers, sent.numbers);
  EXPECT_EQ(got.texts, sent.texts);
}

// The enumerations beyond their first two values (DistinctValues' own), REASON_NONE's 255 too.
TEST(TransportMessages, DiagnosticsRoundTrip) {
  expectEveryFieldRoundTrips<DiagnosticsMessage>([](DiagnosticsMessage& diagnostics) {
    diagnostics.state = HostState::kFault;
    diagnostics.outcomes.front().reason = Reason::kOtherPublisher;
    diagnostics.outcomes.back().reason = Reason::kNone;
  });
}

TEST(TransportMessages, StateRoundTrip) {
  expectEveryFieldRoundTrips<ControllerStateMessage>([](ControllerStateMessage& state) {
    state.state = HostState::kFault;
    state.contact_wrench_source = WrenchSource::kSensor;
  });
}

TEST(TransportMessages, StateWithTheTankOffRoundTripsAsOff) {
  const ControllerStateMessage got = roundTrip(ControllerStateMessage{}).message;
  EXPECT_FALSE(got.passivity);
  EXPECT_EQ(got.tank_energy_j, 0.0);
  EXPECT_EQ(got.gain_fraction, 1.0);
}

}  // namespace
}  // namespace comply::transport
