// sensor_msgs/msg/CompressedImage in CDR (see compressed_image.hpp).

#include "comply/transport/compressed_image.hpp"

#include "cdr_reader.hpp"
#include "cdr_writer.hpp"

namespace comply::transport {

void encodeCdr(const CompressedImageMessage& message, std::vector<std::uint8_t>& out) {
  out.reserve(message.data.size() + message.header.frame_id.size() + 64);
  cdr::Writer w(out);
  w.put(message.header.stamp.sec);
  w.put(message.header.stamp.nanosec);
  w.putString(message.header.frame_id);
  w.putString(message.format);
  w.putSequence(message.data.data(), message.data.size());
  w.finish();
}

bool decodeCdr(std::span<const std::uint8_t> bytes, CompressedImageMessage& message) {
  cdr::Reader r(bytes);
  message.header.stamp.sec = r.get<std::int32_t>();
  message.header.stamp.nanosec = r.get<std::uint32_t>();
  message.header.frame_id = r.getString();
  message.format = r.getString();
  message.data.resize(r.getCount(1));
  r.getArray(message.data.data(), message.data.size());
  return r.ok();
}

}  // namespace comply::transport
