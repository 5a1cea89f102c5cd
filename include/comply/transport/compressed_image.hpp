#pragma once
// sensor_msgs/msg/CompressedImage, the ROS 2 type a recording keeps camera frames in: Foxglove
// shows it, `ros2 bag play` publishes it, and it carries the encoded file (PNG here) as is.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

inline constexpr std::string_view kCompressedImageType = "sensor_msgs/msg/CompressedImage";

struct CompressedImageMessage {
  Header header;       ///< the time the frame shows; frame_id the camera's name
  std::string format;  ///< "png" or "jpeg"
  std::vector<std::uint8_t> data;
};

/// `out` is cleared and then holds the message's CDR bytes (as cdr.hpp's messages).
void encodeCdr(const CompressedImageMessage& message, std::vector<std::uint8_t>& out);
/// False when `bytes` hold no such message (see cdr.hpp's decodeCdr).
bool decodeCdr(std::span<const std::uint8_t> bytes, CompressedImageMessage& message);

}  // namespace comply::transport
