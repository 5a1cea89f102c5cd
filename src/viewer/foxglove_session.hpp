#pragma once
// One client of the Foxglove server, on the server's I/O thread: the HTTP upgrade (subprotocol
// chosen, a plain request or an unknown subprotocol answered and closed), the protocol's greeting,
// the client's subscriptions, and the writer that empties its ClientQueue one message at a time.
// Boost.Beast lives here and in foxglove_server.cpp only.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "client_queue.hpp"
#include "comply/viewer/foxglove_server.hpp"
#include "comply/viewer/rate_limit.hpp"

namespace comply::viewer {

class Session;

/// A channel as the server keeps it; guarded by ServerState::mutex.
struct ChannelEntry {
  ChannelSpec spec;
  ChannelStats stats;
  RateLimit rate;
  std::size_t subscribers = 0;
  SharedPayload latched;
  std::int64_t latched_time_ns = 0;
};

/// What the sessions share with the server. Lock order: this mutex, then a session's. `sessions`
/// holds every connection from its accept on (so that the server's end closes each); only those
/// past the upgrade (`clients` of them) take messages.
struct ServerState {
  std::string name;
  std::string url;
  std::size_t channel_queue_bytes = 0;
  mutable std::mutex mutex;
  std::vector<ChannelEntry> channels;  // a ChannelId is an index
  std::vector<std::weak_ptr<Session>> sessions;
  std::size_t clients = 0;
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(boost::asio::ip::tcp::socket socket, ServerState& server, std::string session_id);
  /// Reads the upgrade request.
  void start();
  /// The server's lock held: queues a channel's message; returns how many older ones it pushed
  /// out of this client's queue.
  std::uint64_t enqueue(ChannelId channel, std::int64_t log_time_ns, const SharedPayload& payload);
  /// The server's lock held: queues protocol text (an advertisement).
  void enqueueText(std::string text);
  /// The server's lock held: says the drops since the last report to the client, if any.
  void reportDrops();
  /// Ends the connection (the server stops).
  void close();

 private:
  void onRequest(boost::beast::error_code error);
  void reply(boost::beast::http::status status, std::string body);
  void onAccept(boost::beast::error_code error);
  void readNext();
  void onRead(boost::beast::error_code error);
  void handleText(const std::string& text);
  void subscribe(const std::vector<std::pair<SubscriptionId, ChannelId>>& subscriptions);
  void unsubscribe(const std::vector<SubscriptionId>& subscriptions);
  void kickLocked();  // the session's lock held
  void writeNext();
  void onWritten(boost::beast::error_code error);
  void fail();

  ServerState& server_;
  std::string session_id_;
  // The connection's executor, kept apart: publishing threads post to it while the I/O thread
  // works on the stream.
  boost::asio::any_io_executor executor_;
  boost::beast::tcp_stream stream_;
  std::optional<boost::beast::websocket::stream<boost::beast::tcp_stream>> socket_;
  boost::beast::flat_buffer buffer_;
  boost::beast::http::request<boost::beast::http::string_body> request_;
  boost::beast::http::response<boost::beast::http::string_body> response_;

  std::mutex mutex_;  // what publishing threads and the I/O thread share
  ClientQueue queue_;
  bool open_ = false;
  bool writing_ = false;
  Outgoing current_;  // the message being written (its buffers live here until done)
};

}  // namespace comply::viewer
