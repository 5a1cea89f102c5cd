// Frames between the host and its transport process (see frames.hpp).

#include "frames.hpp"

#include <sys/socket.h>

#include <cerrno>
#include <cstring>

#include "comply/transport/cdr.hpp"

namespace comply::transport::process {
namespace {

template <typename T>
void appendRaw(const T& value, std::vector<std::uint8_t>& out) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

template <typename T>
bool readRaw(std::span<const std::uint8_t>& bytes, T& value) {
  if (bytes.size() < sizeof(T)) {
    return false;
  }
  std::memcpy(&value, bytes.data(), sizeof(T));
  bytes = bytes.subspan(sizeof(T));
  return true;
}

void appendHead(FrameKind kind, std::size_t payload_bytes, std::vector<std::uint8_t>& out) {
  appendRaw(static_cast<std::uint32_t>(payload_bytes + 1), out);
  out.push_back(static_cast<std::uint8_t>(kind));
}

}  // namespace

void appendFrame(FrameKind kind, std::span<const std::uint8_t> payload,
                 std::vector<std::uint8_t>& out) {
  appendHead(kind, payload.size(), out);
  out.insert(out.end(), payload.begin(), payload.end());
}

void appendFrame(FrameKind kind, std::string_view text, std::vector<std::uint8_t>& out) {
  appendHead(kind, text.size(), out);
  out.insert(out.end(), text.begin(), text.end());
}

void appendFrame(FrameKind kind, std::uint64_t value, std::vector<std::uint8_t>& out) {
  appendHead(kind, sizeof(value), out);
  appendRaw(value, out);
}

void FrameReader::append(std::span<const std::uint8_t> bytes) {
  if (start_ > 0 && start_ == buffer_.size()) {
    buffer_.clear();
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

std::optional<Frame> FrameReader::next() {
  std::span<const std::uint8_t> left(buffer_.data() + start_, buffer_.size() - start_);
  std::uint32_t length = 0;
  if (broken_ || !readRaw(left, length)) {
    return std::nullopt;
  }
  if (length == 0 || length > kMaxFrameBytes) {
    broken_ = true;
    return std::nullopt;
  }
  if (left.size() < length) {
    return std::nullopt;
  }
  Frame frame{static_cast<FrameKind>(left[0]), {left.begin() + 1, left.begin() + length}};
  start_ += sizeof(length) + length;
  if (start_ > buffer_.size() / 2) {  // keep the buffer from growing with the stream
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  return frame;
}

template <typename Message>
void appendSampleFrame(FrameKind kind, const Sample<Message>& sample,
                       std::vector<std::uint8_t>& scratch, std::vector<std::uint8_t>& out) {
  encodeCdr(sample.message, scratch);
  if (scratch.size() + sample.malformed.size() + 64 > kMaxFrameBytes) {
    // A peer's message too large for a frame (a chunk with a megabyte frame_id in every
    // waypoint): handed on as malformed, its stamp kept so that it is accounted, rather than
    // cutting the stream.
    Sample<Message> refused;
    refused.publisher = sample.publisher;
    refused.participant = sample.participant;
    refused.sender = sample.sender;
    refused.message.header.stamp = sample.message.header.stamp;
    refused.refuse(Reason::kTooLarge, "the message is " + std::to_string(scratch.size() >> 20U) +
                                          " MB, more than a comply message can be (" +
                                          std::to_string(kMaxFrameBytes >> 20U) + " MB)");
    appendSampleFrame(kind, refused, scratch, out);
    return;
  }
  const std::size_t payload =
      8 + 8 + sample.sender.size() + 1 + 4 + sample.malformed.size() + scratch.size();
  appendHead(kind, payload, out);
  appendRaw(sample.publisher, out);
  appendRaw(sample.participant, out);
  appendRaw(sample.sender, out);
  appendRaw(static_cast<std::uint8_t>(sample.malformed_reason), out);
  appendRaw(static_cast<std::uint32_t>(sample.malformed.size()), out);
  out.insert(out.end(), sample.malformed.begin(), sample.malformed.end());
  out.insert(out.end(), scratch.begin(), scratch.end());
}

template <typename Message>
bool readSampleFrame(std::span<const std::uint8_t> payload, Sample<Message>& sample) {
  std::uint8_t reason = 0;
  std::uint32_t malformed_bytes = 0;
  if (!readRaw(payload, sample.publisher) || !readRaw(payload, sample.participant) ||
      !readRaw(payload, sample.sender) || !readRaw(payload, reason) ||
      !readRaw(payload, malformed_bytes) || payload.size() < malformed_bytes) {
    return false;
  }
  sample.malformed_reason = static_cast<Reason>(reason);
  sample.malformed.assign(payload.begin(), payload.begin() + malformed_bytes);
  return decodeCdr(payload.subspan(malformed_bytes), sample.message);
}

bool sendAll(int fd, std::span<const std::uint8_t> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n > 0) {
      bytes = bytes.subspan(static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      return false;
    }
  }
  return true;
}

std::optional<std::uint64_t> readU64(std::span<const std::uint8_t> payload) {
  std::uint64_t value = 0;
  if (payload.size() != sizeof(value) || !readRaw(payload, value)) {
    return std::nullopt;
  }
  return value;
}

std::string readText(std::span<const std::uint8_t> payload) {
  return {payload.begin(), payload.end()};
}

#define COMPLY_SAMPLE_FRAMES(Message)                                                            \
  template void appendSampleFrame(FrameKind, const Sample<Message>&, std::vector<std::uint8_t>&, \
                                  std::vector<std::uint8_t>&);                                   \
  template bool readSampleFrame(std::span<const std::uint8_t>, Sample<Message>&);
COMPLY_SAMPLE_FRAMES(CartesianCommandMessage)
COMPLY_SAMPLE_FRAMES(JointCommandMessage)
COMPLY_SAMPLE_FRAMES(CartesianChunkMessage)
COMPLY_SAMPLE_FRAMES(JointChunkMessage)
COMPLY_SAMPLE_FRAMES(RequestMessage)
COMPLY_SAMPLE_FRAMES(CommittedRequestMessage)
#undef COMPLY_SAMPLE_FRAMES

}  // namespace comply::transport::process
