#pragma once
// A Foxglove WebSocket server: what Foxglove, Lichtblick and any client of the Foxglove WebSocket
// protocol connect to for live data. It advertises channels (a topic, its message encoding and
// schema), sends each client the messages of the channels it subscribed to, and nothing else: it
// takes no messages, parameters or service calls from clients.
//
// One I/O thread serves every client; publish() is called from any other thread and never waits
// for a client. Each client has a queue per channel, bounded in bytes: a client slower than a
// channel loses that channel's oldest messages (counted, and said to the client in a status
// message once a second), while the client's writer takes the channels in turn, so a small
// channel is never starved by a big one. Both subprotocol names are accepted,
// `foxglove.sdk.v1` (foxglove_bridge 3 and the Foxglove SDK) and `foxglove.websocket.v1` (older
// clients, Lichtblick).

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace comply::viewer {

/// A server that cannot start (the address taken, not an address).
class ViewerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ServerOptions {
  std::string address = "127.0.0.1";  ///< loopback: other machines need it said
  std::uint16_t port = 8765;          ///< Foxglove's default; 0: any free port (port() tells)
  std::string name = "comply";        ///< shown by the client
  /// Per client and channel: more queued than this and the oldest messages go.
  std::size_t channel_queue_bytes = std::size_t{1} << 20;
};

/// A channel as advertised.
struct ChannelSpec {
  std::string topic;
  std::string encoding;         ///< "cdr", "json"
  std::string schema_name;      ///< "comply_msgs/msg/ControllerState", "foxglove.SceneUpdate"
  std::string schema_encoding;  ///< "ros2msg", "jsonschema"
  std::string schema;           ///< the definition's text
  /// At most this many messages a second reach clients, on average (publish() refuses the rest);
  /// 0: all.
  double max_rate_hz = 0.0;
  /// A new subscriber gets the channel's last message at once (a robot description, a path).
  bool latched = false;
};

/// One channel's account since the server started.
struct ChannelStats {
  std::string topic;
  std::uint64_t published = 0;     ///< accepted by publish()
  std::uint64_t rate_limited = 0;  ///< refused for max_rate_hz, by publish() or wants()
  std::uint64_t sent = 0;          ///< messages written to clients (one per client)
  std::uint64_t dropped = 0;       ///< taken from a slow client's full queue unsent
};

using ChannelId = std::uint32_t;

class FoxgloveServer {
 public:
  /// Listens on options.address:port and starts the I/O thread. Throws ViewerError naming the
  /// address when it cannot.
  explicit FoxgloveServer(const ServerOptions& options);
  ~FoxgloveServer();
  FoxgloveServer(const FoxgloveServer&) = delete;
  FoxgloveServer& operator=(const FoxgloveServer&) = delete;

  /// Advertises a channel to every client, those connected and those to come.
  ChannelId addChannel(const ChannelSpec& spec);
  /// Whether a message on `channel` now would go anywhere: some client subscribes and the
  /// channel's rate allows one (a refusal for the rate counts as rate_limited). Lets a caller
  /// skip encoding what nobody takes.
  [[nodiscard]] bool wants(ChannelId channel);
  /// Queues `payload` (copied once, shared by the clients) for every client subscribed to
  /// `channel`, stamped `log_time_ns`. False when the channel's rate refused it or nobody
  /// subscribes (a latched channel keeps it all the same). Any thread; never waits for a client.
  bool publish(ChannelId channel, std::int64_t log_time_ns, std::span<const std::uint8_t> payload);
  bool publish(ChannelId channel, std::int64_t log_time_ns, std::string_view text);

  [[nodiscard]] std::uint16_t port() const noexcept;
  /// "ws://address:port".
  [[nodiscard]] std::string url() const;
  /// Clients connected now.
  [[nodiscard]] std::size_t clients() const noexcept;
  /// Every channel's account, in the order they were added.
  [[nodiscard]] std::vector<ChannelStats> stats() const;

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace comply::viewer
