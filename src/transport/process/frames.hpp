#pragma once
// What the host and its transport process say to each other over their socket: length-prefixed
// frames, each a kind and a payload. Messages travel as their CDR bytes (cdr.hpp), so the host
// never runs a middleware's deserialiser on what the network sent: only comply's bounds-checked
// decoder on what its own child encoded. Private to the transport.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "comply/transport/host_transport.hpp"

namespace comply::transport::process {

enum class FrameKind : std::uint8_t {
  // transport process -> host
  kReady = 1,   ///< started; payload: describe() text
  kFailed = 2,  ///< could not start; payload: why
  // 3 to 7 and 11: a received sample (sample payload) of each of Inbox::topics(), in its order
  // (kSampleFrameKinds). New kinds are appended, never renumbered.
  kCartesian = 3,
  kJoint = 4,
  kCartesianChunk = 5,
  kJointChunk = 6,
  kRequest = 7,
  kDeparted = 8,   ///< payload: u64 writer that went away
  kHeartbeat = 9,  ///< payload: u64 malformed samples so far
  kFlushed = 10,   ///< payload: u8 1 when every reader had the diagnostics in time
  kCommittedRequest = 11,
  // host -> transport process
  kState = 20,        ///< payload: CDR
  kDiagnostics = 21,  ///< payload: CDR
  kFlush = 22,        ///< payload: f64 timeout [s]
  kCommitted = 23,    ///< payload: CDR, the answer to a committed request
};

/// The kind of frame that carries a sample of each of Inbox::topics(), in its order.
inline constexpr std::array<FrameKind, 6> kSampleFrameKinds{
    FrameKind::kCartesian,  FrameKind::kJoint,   FrameKind::kCartesianChunk,
    FrameKind::kJointChunk, FrameKind::kRequest, FrameKind::kCommittedRequest};
static_assert(std::tuple_size_v<decltype(Inbox{}.topics())> == kSampleFrameKinds.size(),
              "one sample frame kind per topic of the inbox");

/// The kind of frame that carries a sample of topic `topic` of Inbox::topics().
constexpr FrameKind sampleFrameKind(int topic) {
  return kSampleFrameKinds.at(static_cast<std::size_t>(topic));
}

/// A frame larger than this is a broken peer, not a message (a 64-waypoint chunk is ~80 kB).
inline constexpr std::size_t kMaxFrameBytes = 16U << 20U;

struct Frame {
  FrameKind kind{};
  std::vector<std::uint8_t> payload;
};

/// Appends one frame (length, kind, payload) to `out`.
void appendFrame(FrameKind kind, std::span<const std::uint8_t> payload,
                 std::vector<std::uint8_t>& out);
void appendFrame(FrameKind kind, std::string_view text, std::vector<std::uint8_t>& out);
void appendFrame(FrameKind kind, std::uint64_t value, std::vector<std::uint8_t>& out);

/// The bytes of a stream cut into frames as they arrive.
class FrameReader {
 public:
  void append(std::span<const std::uint8_t> bytes);
  /// The next whole frame, if one has arrived. Sets broken() on a frame longer than
  /// kMaxFrameBytes or of length 0 (the stream is then not to be read further).
  std::optional<Frame> next();
  [[nodiscard]] bool broken() const noexcept { return broken_; }

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t start_ = 0;
  bool broken_ = false;
};

/// A received sample as a frame: the writer, its participant and sender, what did not fit and the
/// reason it is refused with, the CDR bytes.
template <typename Message>
void appendSampleFrame(FrameKind kind, const Sample<Message>& sample,
                       std::vector<std::uint8_t>& scratch, std::vector<std::uint8_t>& out);
/// The sample a frame of appendSampleFrame holds; false when it holds none.
template <typename Message>
bool readSampleFrame(std::span<const std::uint8_t> payload, Sample<Message>& sample);

/// Writes `bytes` whole to the socket `fd` (retrying a send cut short or interrupted); false when
/// the socket refused (its peer gone, or its send timeout passed).
bool sendAll(int fd, std::span<const std::uint8_t> bytes);

/// A u64 payload (kDeparted, kHeartbeat); nullopt when the payload is not 8 bytes.
std::optional<std::uint64_t> readU64(std::span<const std::uint8_t> payload);
std::string readText(std::span<const std::uint8_t> payload);

}  // namespace comply::transport::process
