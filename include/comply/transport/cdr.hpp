#pragma once
// Each live message as the CDR bytes ROS 2 puts on the wire (XCDR1, little endian, with the
// encapsulation header): what DDS sends, byte for byte (tests/transport holds them against
// CycloneDDS's own serialisation), and what a recording stores, so `ros2 bag play` and Foxglove
// read a recording with the comply_msgs definitions alone. Plus those definitions, as rosbag2
// stores them in a file (the .msg text with its dependencies appended).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

/// `out` is cleared and then holds the message's CDR bytes.
void encodeCdr(const ControllerStateMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CommandOutcomeMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const ChunkTimingMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const DiagnosticsMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CartesianCommandMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const JointCommandMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CartesianChunkMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const JointChunkMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const RequestMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CycleRecordMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CommittedRequestMessage& message, std::vector<std::uint8_t>& out);
void encodeCdr(const CommittedMessage& message, std::vector<std::uint8_t>& out);

/// The message `bytes` hold, as encodeCdr writes it, into `message`. False when they hold none:
/// another encoding, cut short, a count past the end, a joint vector longer than kMaxDof, a chunk
/// (or an answer's list) longer than kMaxChunkWaypoints; `message` is then not to be used. (A DDS
/// reader decodes with CycloneDDS; these read what comply's own processes hand each other.)
bool decodeCdr(std::span<const std::uint8_t> bytes, ControllerStateMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, DiagnosticsMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, CartesianCommandMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, JointCommandMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, CartesianChunkMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, JointChunkMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, RequestMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, CommittedRequestMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, CommittedMessage& message);
bool decodeCdr(std::span<const std::uint8_t> bytes, CycleRecordMessage& message);

/// The ROS 2 type name of each message ("comply_msgs/msg/ControllerState").
template <typename Message>
std::string_view rosTypeName();

/// The definition of `type` ("comply_msgs/msg/Diagnostics" or "comply_msgs/Diagnostics") as an
/// MCAP schema of encoding "ros2msg" holds it: its .msg text, then for every type it uses,
/// directly or not, a line of 80 '=', "MSG: pkg/Type" and that type's text. Throws
/// std::out_of_range for a type comply does not define.
std::string ros2MessageDefinition(std::string_view type);

}  // namespace comply::transport
