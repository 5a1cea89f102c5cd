#pragma once
// The host's side of the frames it exchanges with its transport process (frames.hpp): what the
// process sends, turned into Inbox samples and what the process says of itself (ready, failed,
// alive, flushed), and what the host publishes, turned into frames. Nothing here knows the
// process: supervisor.hpp feeds the bytes and acts on what they said. Private to the transport.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "comply/transport/cdr.hpp"
#include "comply/transport/host_transport.hpp"
#include "frames.hpp"

namespace comply::transport::process {

/// The stream of one process after another, cut into frames and handled: samples into the
/// caller's Inbox, the rest kept here. Used under the reader's lock, except description() and
/// malformedSamples(), which any thread may call.
class IncomingFrames {
 public:
  /// A new process: its stream and what it said start afresh. The writers the last one had seen
  /// were handed on when it ended (processEnded()).
  void restart();
  void append(std::span<const std::uint8_t> bytes) { reader_.append(bytes); }
  /// Handles the next whole frame that has arrived: a sample into its topic's list of `inbox`, a
  /// departed writer into inbox.departed, anything else kept here. Its kind; nullopt when no
  /// whole frame waits.
  std::optional<FrameKind> handleNext(Inbox& inbox);
  /// The stream cannot be read further: a frame too long, a sample that does not decode, a kind
  /// the host does not take.
  [[nodiscard]] bool broken() const noexcept { return reader_.broken() || broken_; }
  [[nodiscard]] bool ready() const noexcept { return ready_; }
  /// Why the process could not start, as it said (empty: it did not say).
  [[nodiscard]] const std::string& failure() const noexcept { return failure_; }
  /// The process's describe() of its transport, as its last ready frame said.
  [[nodiscard]] std::string description() const;

  /// A flush was asked for: forgets the answer to the last.
  void expectFlushed() { flushed_.reset(); }
  /// The answer to the flush asked for: true when every reader had the diagnostics in time;
  /// nullopt until it comes.
  [[nodiscard]] std::optional<bool> flushed() const { return flushed_; }

  /// The process ended: its count of malformed samples is kept, and every writer it had seen is
  /// appended to `departed` (a restarted process sees them anew, under other handles).
  void processEnded(std::vector<std::uint64_t>& departed);
  /// Malformed samples of every process so far.
  [[nodiscard]] std::uint64_t malformedSamples() const {
    return malformed_ended_.load() + malformed_current_.load();
  }

 private:
  void takeSample(const Frame& frame, Inbox& inbox);
  template <typename Message>
  void take(const Frame& frame, std::vector<Sample<Message>>& into);

  FrameReader reader_;
  bool broken_ = false;
  bool ready_ = false;
  std::string failure_;
  std::optional<bool> flushed_;
  std::set<std::uint64_t> publishers_;  ///< writers seen from the current process

  mutable std::mutex description_mutex_;
  std::string description_;
  std::atomic<std::uint64_t> malformed_ended_{0};
  std::atomic<std::uint64_t> malformed_current_{0};
};

/// What the host sends the process, as frames. The buffers are kept from one frame to the next:
/// once grown, publishing allocates nothing. Used under the sender's lock.
class OutgoingFrames {
 public:
  /// `message` in CDR, in one frame of `kind`; valid until the next call.
  template <typename Message>
  const std::vector<std::uint8_t>& encode(FrameKind kind, const Message& message) {
    encodeCdr(message, cdr_);
    out_.clear();
    appendFrame(kind, cdr_, out_);
    return out_;
  }
  /// A request to flush: the process answers within `timeout_s` whether every reader had the
  /// diagnostics.
  static std::vector<std::uint8_t> flushRequest(double timeout_s);

 private:
  std::vector<std::uint8_t> cdr_;
  std::vector<std::uint8_t> out_;
};

}  // namespace comply::transport::process
