// The host's side of the transport process's frames (see frame_adapter.hpp).

#include "frame_adapter.hpp"

#include <cstring>

namespace comply::transport::process {

void IncomingFrames::restart() {
  reader_ = FrameReader();
  broken_ = false;
  ready_ = false;
  failure_.clear();
  malformed_current_ = 0;
}

std::optional<FrameKind> IncomingFrames::handleNext(Inbox& inbox) {
  const std::optional<Frame> frame = reader_.next();
  if (!frame) {
    return std::nullopt;
  }
  switch (frame->kind) {
    case FrameKind::kReady: {
      const std::lock_guard<std::mutex> lock(description_mutex_);
      description_ = readText(frame->payload);
      ready_ = true;
      break;
    }
    case FrameKind::kFailed:
      failure_ = readText(frame->payload);
      break;
    case FrameKind::kDeparted:
      if (const auto writer = readU64(frame->payload)) {
        publishers_.erase(*writer);
        inbox.departed.push_back(*writer);
      }
      break;
    case FrameKind::kHeartbeat:
      if (const auto malformed = readU64(frame->payload)) {
        malformed_current_ = *malformed;
      }
      break;
    case FrameKind::kFlushed:
      flushed_ = !frame->payload.empty() && frame->payload[0] != 0;
      break;
    default:
      takeSample(*frame, inbox);
      break;
  }
  return frame->kind;
}

std::string IncomingFrames::description() const {
  const std::lock_guard<std::mutex> lock(description_mutex_);
  return description_;
}

void IncomingFrames::processEnded(std::vector<std::uint64_t>& departed) {
  malformed_ended_ += malformed_current_.exchange(0);
  for (const std::uint64_t writer : publishers_) {
    departed.push_back(writer);
  }
  publishers_.clear();
}

/// A sample frame into its topic's list; any other kind breaks the stream.
void IncomingFrames::takeSample(const Frame& frame, Inbox& inbox) {
  bool taken = false;
  forEachTopic(inbox.topics(), [&](int topic, auto& samples) {
    if (frame.kind == sampleFrameKind(topic)) {
      take(frame, samples);
      taken = true;
    }
  });
  if (!taken) {
    broken_ = true;
  }
}

template <typename Message>
void IncomingFrames::take(const Frame& frame, std::vector<Sample<Message>>& into) {
  Sample<Message> sample;
  if (readSampleFrame(frame.payload, sample)) {
    publishers_.insert(sample.publisher);
    into.push_back(std::move(sample));
  } else {
    broken_ = true;
  }
}

std::vector<std::uint8_t> OutgoingFrames::flushRequest(double timeout_s) {
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> payload(sizeof(double));
  std::memcpy(payload.data(), &timeout_s, sizeof(double));
  appendFrame(FrameKind::kFlush, payload, frame);
  return frame;
}

}  // namespace comply::transport::process
