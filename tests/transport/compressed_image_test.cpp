// sensor_msgs/CompressedImage, the type a recording keeps camera frames in: comply's encoder
// against CycloneDDS's serialisation of the same message (the rosidl IDL, idl/ here), its
// decoder, and its definition as a recording's schema.

#include "comply/transport/compressed_image.hpp"

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include "comply/transport/cdr.hpp"
#include "comply/transport/participant.hpp"
#include "loopback.hpp"
#include "sensor_msgs/msg/CompressedImage.h"

namespace comply::transport {
namespace {

/// `message` serialised by CycloneDDS: written to a reader of a loopback participant, taken as
/// CDR.
std::vector<std::uint8_t> wireBytes(const CompressedImageMessage& message) {
  const Participant participant({.domain_id = testDomain()});
  const dds_entity_t topic =
      dds_create_topic(participant.handle(), &sensor_msgs_msg_dds__CompressedImage__desc,
                       "rt/compressed_image_test", nullptr, nullptr);
  const dds_entity_t writer = dds_create_writer(participant.handle(), topic, nullptr, nullptr);
  const dds_entity_t reader = dds_create_reader(participant.handle(), topic, nullptr, nullptr);
  EXPECT_GT(topic, 0);
  EXPECT_GT(writer, 0);
  EXPECT_GT(reader, 0);
  for (int i = 0; i < 500; ++i) {  // until the reader is matched, at most 5 s
    dds_publication_matched_status_t matched;
    if (dds_get_publication_matched_status(writer, &matched) == 0 && matched.current_count > 0) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  sensor_msgs_msg_dds__CompressedImage_ sample{};
  sample.header.stamp.sec = message.header.stamp.sec;
  sample.header.stamp.nanosec = message.header.stamp.nanosec;
  std::string frame_id = message.header.frame_id;
  std::string format = message.format;
  std::vector<std::uint8_t> data = message.data;
  sample.header.frame_id = frame_id.data();
  sample.format = format.data();
  sample.data._length = static_cast<std::uint32_t>(data.size());
  sample.data._maximum = sample.data._length;
  sample.data._buffer = data.data();
  sample.data._release = false;
  EXPECT_EQ(dds_write(writer, &sample), DDS_RETCODE_OK);
  for (int i = 0; i < 500; ++i) {  // until the sample has arrived, at most 5 s
    uint32_t status = 0;
    if (dds_take_status(reader, &status, DDS_DATA_AVAILABLE_STATUS) == 0 && status != 0) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return takeSerialized(reader);
}

TEST(CompressedImage, EncoderMatchesCycloneDdsAndTheDecoderReadsItBack) {
  // Lengths of 0 to 6 data bytes and odd string lengths: every padding case of the sequence
  // after the format string, and of the message's end.
  for (std::size_t size = 0; size < 7; ++size) {
    CompressedImageMessage message;
    message.header = {{-5, 123'456'789}, size % 2 == 0 ? "front" : "wrist_cam"};
    message.format = size % 3 == 0 ? "png" : "jpeg";
    for (std::size_t i = 0; i < size; ++i) {
      message.data.push_back(static_cast<std::uint8_t>(0xA0 + i));
    }
    std::vector<std::uint8_t> encoded;
    encodeCdr(message, encoded);
    const std::vector<std::uint8_t> wire = wireBytes(message);
    EXPECT_EQ(encoded, wire) << size << " data bytes";

    CompressedImageMessage decoded;
    ASSERT_TRUE(decodeCdr(wire, decoded)) << size;
    EXPECT_EQ(decoded.header.stamp.sec, -5);
    EXPECT_EQ(decoded.header.stamp.nanosec, 123'456'789U);
    EXPECT_EQ(decoded.header.frame_id, message.header.frame_id);
    EXPECT_EQ(decoded.format, message.format);
    EXPECT_EQ(decoded.data, message.data);
    // Every cut short of the data's end is refused.
    const std::size_t padding = wire[3] & 3U;
    for (std::size_t cut = 0; cut + padding < wire.size(); ++cut) {
      CompressedImageMessage part;
      EXPECT_FALSE(decodeCdr(std::span(wire.data(), cut), part)) << cut << " of " << wire.size();
    }
  }
}

TEST(CompressedImage, ADataCountPastTheEndIsRefused) {
  CompressedImageMessage message;
  message.format = "png";
  message.data = {1, 2, 3, 4};
  std::vector<std::uint8_t> bytes;
  encodeCdr(message, bytes);
  // The count sits right before the four data bytes.
  const std::size_t count_at = bytes.size() - 4 - 4;
  const std::uint32_t huge = 1U << 30;
  std::memcpy(bytes.data() + count_at, &huge, sizeof huge);
  CompressedImageMessage decoded;
  EXPECT_FALSE(decodeCdr(bytes, decoded));
}

TEST(CompressedImage, DefinitionIsRos2sWithItsHeader) {
  const std::string definition = ros2MessageDefinition(kCompressedImageType);
  EXPECT_EQ(definition.find("std_msgs/Header header\nstring format\nuint8[] data\n"), 0U)
      << definition;
  EXPECT_NE(definition.find("MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp"),
            std::string::npos)
      << definition;
  EXPECT_NE(definition.find("MSG: builtin_interfaces/Time\nint32 sec"), std::string::npos);
}

}  // namespace
}  // namespace comply::transport
