#pragma once
// What one client of the Foxglove server has yet to receive: the protocol's text messages
// (advertisements, status) first, then the subscribed channels' messages, the channels taken in
// turn so that a channel with a message waiting is written within one round of the others, however
// much a big one has queued. Each channel's queue is bounded in bytes: past the bound the oldest
// go (the newest always stays), counted for the client's status message and the channel's stats.
// Not thread-safe: the session holds its lock around it.

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "comply/viewer/foxglove_server.hpp"

namespace comply::viewer {

using SubscriptionId = std::uint32_t;
using SharedPayload = std::shared_ptr<const std::vector<std::uint8_t>>;

/// A message ready to write: protocol text, or a channel's message as the binary messageData
/// frame (its 13-byte header for this client's subscription, then the shared payload).
struct OutgoingText {
  std::string text;
};
struct OutgoingData {
  ChannelId channel = 0;
  std::array<std::uint8_t, 13> header{};
  SharedPayload payload;
};
using Outgoing = std::variant<OutgoingText, OutgoingData>;

/// Messages of a channel dropped for one client since the last report.
struct DropReport {
  ChannelId channel = 0;
  std::uint64_t dropped = 0;
};

class ClientQueue {
 public:
  explicit ClientQueue(std::size_t channel_queue_bytes) : limit_bytes_(channel_queue_bytes) {}

  /// False when `channel` already has a subscription of this client.
  bool subscribe(ChannelId channel, SubscriptionId subscription);
  /// The channel it was for; none when `subscription` is not this client's. Its queue goes.
  std::optional<ChannelId> unsubscribe(SubscriptionId subscription);
  [[nodiscard]] bool subscribed(ChannelId channel) const { return channels_.contains(channel); }
  /// The channels subscribed to, for the server's counts when the client leaves.
  [[nodiscard]] std::vector<ChannelId> channels() const;

  /// False (and nothing queued) when kMaxTexts wait already: a client that sends and never reads
  /// does not grow the server's memory with the answers.
  bool pushText(std::string text);
  static constexpr std::size_t kMaxTexts = 1024;
  /// Queues a message of a subscribed channel (else nothing); returns how many older ones of the
  /// channel it pushed out.
  std::uint64_t push(ChannelId channel, std::int64_t log_time_ns, SharedPayload payload);
  /// The next message to write; false when nothing waits.
  bool pop(Outgoing& out);
  /// The drops since the last call, per channel that had any.
  std::vector<DropReport> takeDrops();
  [[nodiscard]] std::size_t queuedBytes(ChannelId channel) const;

 private:
  struct Queued {
    std::int64_t log_time_ns;
    SharedPayload payload;
  };
  struct ChannelQueue {
    SubscriptionId subscription = 0;
    std::deque<Queued> messages;
    std::size_t bytes = 0;
    std::uint64_t dropped_unreported = 0;
  };

  std::size_t limit_bytes_;
  std::deque<std::string> texts_;
  std::map<ChannelId, ChannelQueue> channels_;
  std::optional<ChannelId> last_served_;
};

/// The messageData frame's header: opcode 1, the subscription, the log time (little-endian).
std::array<std::uint8_t, 13> messageDataHeader(SubscriptionId subscription,
                                               std::int64_t log_time_ns);

}  // namespace comply::viewer
