// One client of the Foxglove server (see foxglove_session.hpp).

#include "foxglove_session.hpp"

#include <boost/asio/post.hpp>
#include <sstream>

#include "protocol_json.hpp"

namespace comply::viewer {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

namespace {
constexpr int kSendBufferBytes = 64 * 1024;
}  // namespace

Session::Session(asio::ip::tcp::socket socket, ServerState& server, std::string session_id)
    : server_(server),
      session_id_(std::move(session_id)),
      executor_(socket.get_executor()),
      stream_(std::move(socket)),
      queue_(server.channel_queue_bytes) {}

void Session::start() {
  stream_.expires_after(std::chrono::seconds(10));  // a client that never finishes its request
  http::async_read(stream_, buffer_, request_,
                   [self = shared_from_this()](beast::error_code error, std::size_t) {
                     self->onRequest(error);
                   });
}

void Session::onRequest(beast::error_code error) {
  if (error) {
    return;
  }
  if (!websocket::is_upgrade(request_)) {
    reply(http::status::ok, "comply: a Foxglove WebSocket server. Open Foxglove or Lichtblick, " +
                                std::string("choose \"Foxglove WebSocket\" and connect to ") +
                                server_.url + "\n");
    return;
  }
  const std::string offered(request_[http::field::sec_websocket_protocol]);
  const std::optional<std::string> subprotocol = chooseSubprotocol(offered);
  if (!subprotocol) {
    reply(http::status::bad_request,
          "comply speaks the Foxglove WebSocket protocol: offer the subprotocol " +
              std::string(kSubprotocolSdk) + " or " + std::string(kSubprotocolWebsocket) +
              " (offered: \"" + offered + "\")\n");
    return;
  }
  stream_.expires_never();
  socket_.emplace(std::move(stream_));
  // A viewer that only listens sends nothing: pinged after 15 s of silence, and let go at 30 s
  // only when it answers nothing (a browser answers pings by itself).
  auto timeout = websocket::stream_base::timeout::suggested(beast::role_type::server);
  timeout.idle_timeout = std::chrono::seconds(30);
  timeout.keep_alive_pings = true;
  socket_->set_option(timeout);
  socket_->set_option(
      websocket::stream_base::decorator([name = *subprotocol](websocket::response_type& response) {
        response.set(http::field::sec_websocket_protocol, name);
        response.set(http::field::server, "comply");
      }));
  auto& tcp = beast::get_lowest_layer(*socket_).socket();
  tcp.set_option(asio::ip::tcp::no_delay(true));
  // What the kernel holds for a client is out of the queues' turn-taking: a large send buffer
  // filled by a big channel would hold a small channel's next message behind megabytes.
  tcp.set_option(asio::socket_base::send_buffer_size(kSendBufferBytes));
  socket_->async_accept(request_, [self = shared_from_this()](beast::error_code accept_error) {
    self->onAccept(accept_error);
  });
}

void Session::reply(http::status status, std::string body) {
  response_ = http::response<http::string_body>(status, request_.version());
  response_.set(http::field::server, "comply");
  response_.set(http::field::content_type, "text/plain; charset=utf-8");
  response_.keep_alive(false);
  response_.body() = std::move(body);
  response_.prepare_payload();
  http::async_write(
      stream_, response_, [self = shared_from_this()](beast::error_code, std::size_t) {
        beast::error_code ignored;
        self->stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
      });
}

void Session::onAccept(beast::error_code error) {
  if (error) {
    return;
  }
  {
    const std::lock_guard server_lock(server_.mutex);
    std::vector<std::pair<ChannelId, ChannelSpec>> channels;
    for (std::size_t id = 0; id < server_.channels.size(); ++id) {
      channels.emplace_back(static_cast<ChannelId>(id), server_.channels[id].spec);
    }
    ++server_.clients;
    const std::lock_guard lock(mutex_);
    open_ = true;
    queue_.pushText(serverInfoJson(server_.name, session_id_));
    queue_.pushText(advertiseJson(channels));
    kickLocked();
  }
  readNext();
}

void Session::readNext() {
  socket_->async_read(buffer_, [self = shared_from_this()](beast::error_code error, std::size_t) {
    self->onRead(error);
  });
}

void Session::onRead(beast::error_code error) {
  if (error) {
    fail();
    return;
  }
  if (socket_->got_text()) {
    handleText(beast::buffers_to_string(buffer_.data()));
  } else {
    const std::lock_guard lock(mutex_);
    queue_.pushText(statusJson(StatusLevel::kError,
                               "comply takes no messages over this connection: send commands "
                               "with `comply send` or the Python client"));
    kickLocked();
  }
  buffer_.consume(buffer_.size());
  readNext();
}

void Session::handleText(const std::string& text) {
  try {
    const ClientOp op = parseClientOp(text);
    if (const auto* subscribe_op = std::get_if<SubscribeOp>(&op)) {
      subscribe(subscribe_op->subscriptions);
    } else if (const auto* unsubscribe_op = std::get_if<UnsubscribeOp>(&op)) {
      unsubscribe(unsubscribe_op->subscriptions);
    } else {
      const std::lock_guard lock(mutex_);
      queue_.pushText(statusJson(StatusLevel::kError, "comply does not take \"" +
                                                          std::get<OtherOp>(op).op +
                                                          "\": it serves subscriptions only"));
      kickLocked();
    }
  } catch (const ProtocolError& refusal) {
    const std::lock_guard lock(mutex_);
    queue_.pushText(statusJson(StatusLevel::kError,
                               std::string("comply could not read a message: ") + refusal.what()));
    kickLocked();
  }
}

void Session::subscribe(const std::vector<std::pair<SubscriptionId, ChannelId>>& subscriptions) {
  const std::lock_guard server_lock(server_.mutex);
  const std::lock_guard lock(mutex_);
  if (!open_) {
    return;  // a read that completed after the connection failed: its counts are settled
  }
  for (const auto& [subscription, channel] : subscriptions) {
    if (channel >= server_.channels.size()) {
      queue_.pushText(statusJson(StatusLevel::kError,
                                 "no channel " + std::to_string(channel) + " to subscribe to"));
      continue;
    }
    ChannelEntry& entry = server_.channels[channel];
    if (!queue_.subscribe(channel, subscription)) {
      queue_.pushText(statusJson(StatusLevel::kError, "subscription " +
                                                          std::to_string(subscription) + " to " +
                                                          entry.spec.topic + " refused: the " +
                                                          "channel or the id is already in use"));
      continue;
    }
    ++entry.subscribers;
    if (entry.latched) {
      queue_.push(channel, entry.latched_time_ns, entry.latched);
    }
  }
  kickLocked();
}

void Session::unsubscribe(const std::vector<SubscriptionId>& subscriptions) {
  const std::lock_guard server_lock(server_.mutex);
  const std::lock_guard lock(mutex_);
  if (!open_) {
    return;
  }
  for (const SubscriptionId subscription : subscriptions) {
    if (const std::optional<ChannelId> channel = queue_.unsubscribe(subscription)) {
      --server_.channels[*channel].subscribers;
    }
  }
}

std::uint64_t Session::enqueue(ChannelId channel, std::int64_t log_time_ns,
                               const SharedPayload& payload) {
  const std::lock_guard lock(mutex_);
  if (!open_ || !queue_.subscribed(channel)) {
    return 0;
  }
  const std::uint64_t dropped = queue_.push(channel, log_time_ns, payload);
  kickLocked();
  return dropped;
}

void Session::enqueueText(std::string text) {
  const std::lock_guard lock(mutex_);
  if (open_) {
    queue_.pushText(std::move(text));
    kickLocked();
  }
}

void Session::reportDrops() {
  const std::lock_guard lock(mutex_);
  const std::vector<DropReport> drops = queue_.takeDrops();
  if (drops.empty() || !open_) {
    return;
  }
  std::ostringstream message;
  message << "comply: this connection is slower than what it subscribed to; messages dropped "
             "since the last notice (oldest first, "
          << server_.channel_queue_bytes / 1024 << " KiB queued at most per channel):";
  for (const DropReport& drop : drops) {
    message << " " << server_.channels[drop.channel].spec.topic << " " << drop.dropped << ";";
  }
  queue_.pushText(statusJson(StatusLevel::kWarning, message.str()));
  kickLocked();
}

void Session::kickLocked() {
  if (writing_ || !open_) {
    return;
  }
  writing_ = true;
  asio::post(executor_, [self = shared_from_this()] { self->writeNext(); });
}

void Session::writeNext() {
  {
    const std::lock_guard lock(mutex_);
    if (!open_ || !queue_.pop(current_)) {
      writing_ = false;
      return;
    }
  }
  auto done = [self = shared_from_this()](beast::error_code error, std::size_t) {
    self->onWritten(error);
  };
  if (const auto* text = std::get_if<OutgoingText>(&current_)) {
    socket_->text(true);
    socket_->async_write(asio::buffer(text->text), std::move(done));
  } else {
    const auto& data = std::get<OutgoingData>(current_);
    socket_->binary(true);
    const std::array<asio::const_buffer, 2> frame{asio::buffer(data.header),
                                                  asio::buffer(*data.payload)};
    socket_->async_write(frame, std::move(done));
  }
}

void Session::onWritten(beast::error_code error) {
  if (error) {
    fail();
    return;
  }
  if (const auto* data = std::get_if<OutgoingData>(&current_)) {
    const std::lock_guard server_lock(server_.mutex);
    ++server_.channels[data->channel].stats.sent;
  }
  current_ = OutgoingText{};
  writeNext();
}

void Session::fail() {
  const std::lock_guard server_lock(server_.mutex);
  const std::lock_guard lock(mutex_);
  if (!open_) {
    return;
  }
  open_ = false;
  --server_.clients;
  for (const ChannelId channel : queue_.channels()) {
    --server_.channels[channel].subscribers;
  }
}

void Session::close() {
  if (socket_) {
    beast::error_code ignored;
    beast::get_lowest_layer(*socket_).socket().close(ignored);
  } else {
    beast::error_code ignored;
    stream_.socket().close(ignored);
  }
}

}  // namespace comply::viewer
