// The Foxglove server: its listening socket, I/O thread and channels (see foxglove_server.hpp).

#include "comply/viewer/foxglove_server.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <random>
#include <thread>

#include "foxglove_session.hpp"
#include "protocol_json.hpp"

namespace comply::viewer {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;

class FoxgloveServer::Impl {
 public:
  explicit Impl(const ServerOptions& options)
      : acceptor_(io_), drop_timer_(io_), retry_timer_(io_) {
    state_.name = options.name;
    state_.channel_queue_bytes = options.channel_queue_bytes;
    boost::system::error_code error;
    const asio::ip::address address = asio::ip::make_address(options.address, error);
    if (error) {
      throw ViewerError("the viewer's address \"" + options.address +
                        "\" is not an IP address: " + error.message());
    }
    const asio::ip::tcp::endpoint endpoint(address, options.port);
    const std::string where = options.address + ":" + std::to_string(options.port);
    acceptor_.open(endpoint.protocol(), error);
    if (!error) {
      acceptor_.set_option(asio::socket_base::reuse_address(true), error);
    }
    if (!error) {
      acceptor_.bind(endpoint, error);
    }
    if (!error) {
      acceptor_.listen(asio::socket_base::max_listen_connections, error);
    }
    if (error) {
      throw ViewerError("the viewer cannot listen on " + where + ": " + error.message() +
                        (error == asio::error::address_in_use
                             ? " (another program, or another comply, serves it: choose another "
                               "port)"
                         : error == asio::error::access_denied
                             ? " (ports below 1024 need privileges: choose another, e.g. 8765)"
                             : ""));
    }
    port_ = acceptor_.local_endpoint().port();
    // An IPv6 address goes in brackets in a URL.
    const bool v6 = options.address.find(':') != std::string::npos;
    state_.url = "ws://" + (v6 ? "[" + options.address + "]" : options.address) + ":" +
                 std::to_string(port_);
    session_prefix_ = std::to_string(std::random_device{}());
    accept();
    reportDropsLater();
    thread_ = std::thread([this] { io_.run(); });
  }

  ~Impl() {
    asio::post(io_, [this] {
      stopping_ = true;  // a timer or accept completion already queued does not re-arm
      boost::system::error_code ignored;
      acceptor_.close(ignored);
      drop_timer_.cancel();
      retry_timer_.cancel();
      const std::lock_guard lock(state_.mutex);
      for (const std::weak_ptr<Session>& weak : state_.sessions) {
        if (const std::shared_ptr<Session> session = weak.lock()) {
          session->close();
        }
      }
    });
    thread_.join();
  }

  ChannelId addChannel(const ChannelSpec& spec) {
    const std::lock_guard lock(state_.mutex);
    const auto id = static_cast<ChannelId>(state_.channels.size());
    ChannelEntry& entry = state_.channels.emplace_back();
    entry.spec = spec;
    entry.stats.topic = spec.topic;
    entry.rate = RateLimit(spec.max_rate_hz);
    const std::string advertisement = advertiseJson({{id, spec}});
    forEachSession([&](Session& session) { session.enqueueText(advertisement); });
    return id;
  }

  bool wants(ChannelId channel) {
    const std::lock_guard lock(state_.mutex);
    ChannelEntry& entry = state_.channels.at(channel);
    if (entry.subscribers == 0) {
      return false;
    }
    if (!entry.rate.allows(Clock::now())) {
      ++entry.stats.rate_limited;
      return false;
    }
    return true;
  }

  bool publish(ChannelId channel, std::int64_t log_time_ns, const std::uint8_t* data,
               std::size_t size) {
    const std::lock_guard lock(state_.mutex);
    ChannelEntry& entry = state_.channels.at(channel);
    const Clock::time_point now = Clock::now();
    if (!entry.rate.allows(now)) {
      ++entry.stats.rate_limited;
      return false;
    }
    if (entry.subscribers == 0 && !entry.spec.latched) {
      return false;
    }
    entry.rate.take(now);
    ++entry.stats.published;
    auto payload = std::make_shared<const std::vector<std::uint8_t>>(data, data + size);
    if (entry.spec.latched) {
      entry.latched = payload;
      entry.latched_time_ns = log_time_ns;
    }
    forEachSession([&](Session& session) {
      entry.stats.dropped += session.enqueue(channel, log_time_ns, payload);
    });
    return entry.subscribers > 0;
  }

  std::vector<ChannelStats> stats() const {
    const std::lock_guard lock(state_.mutex);
    std::vector<ChannelStats> all;
    for (const ChannelEntry& entry : state_.channels) {
      all.push_back(entry.stats);
    }
    return all;
  }

  std::size_t clients() const {
    const std::lock_guard lock(state_.mutex);
    return state_.clients;
  }

  std::uint16_t port() const noexcept { return port_; }
  const std::string& url() const noexcept { return state_.url; }

 private:
  /// The state's lock held; forgets the sessions that ended.
  template <typename Visit>
  void forEachSession(Visit&& visit) {
    std::erase_if(state_.sessions,
                  [](const std::weak_ptr<Session>& weak) { return weak.expired(); });
    for (const std::weak_ptr<Session>& weak : state_.sessions) {
      if (const std::shared_ptr<Session> session = weak.lock()) {
        visit(*session);
      }
    }
  }

  void accept() {
    acceptor_.async_accept([this](boost::system::error_code error, asio::ip::tcp::socket socket) {
      if (stopping_ || error == asio::error::operation_aborted) {
        return;
      }
      if (error) {
        // Out of file descriptors, say: try again in a while, not in a loop that eats a core.
        retry_timer_.expires_after(std::chrono::milliseconds(100));
        retry_timer_.async_wait([this](boost::system::error_code wait_error) {
          if (!wait_error && !stopping_) {
            accept();
          }
        });
        return;
      }
      const auto session = std::make_shared<Session>(
          std::move(socket), state_, session_prefix_ + "-" + std::to_string(++sessions_started_));
      {
        const std::lock_guard lock(state_.mutex);
        forEachSession([](Session&) {});  // forgets the ended ones
        state_.sessions.push_back(session);
      }
      session->start();
      accept();
    });
  }

  void reportDropsLater() {
    drop_timer_.expires_after(std::chrono::seconds(1));
    drop_timer_.async_wait([this](boost::system::error_code error) {
      if (error || stopping_) {
        return;
      }
      {
        const std::lock_guard lock(state_.mutex);
        forEachSession([](Session& session) { session.reportDrops(); });
      }
      reportDropsLater();
    });
  }

  ServerState state_;  // outlives the I/O context, whose handlers hold sessions that refer to it
  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_;
  asio::steady_timer drop_timer_;
  asio::steady_timer retry_timer_;
  bool stopping_ = false;  // the I/O thread's
  std::uint16_t port_ = 0;
  std::string session_prefix_;
  std::uint64_t sessions_started_ = 0;
  std::thread thread_;
};

FoxgloveServer::FoxgloveServer(const ServerOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

FoxgloveServer::~FoxgloveServer() = default;

ChannelId FoxgloveServer::addChannel(const ChannelSpec& spec) {
  return impl_->addChannel(spec);
}

bool FoxgloveServer::wants(ChannelId channel) {
  return impl_->wants(channel);
}

bool FoxgloveServer::publish(ChannelId channel, std::int64_t log_time_ns,
                             std::span<const std::uint8_t> payload) {
  return impl_->publish(channel, log_time_ns, payload.data(), payload.size());
}

bool FoxgloveServer::publish(ChannelId channel, std::int64_t log_time_ns, std::string_view text) {
  return impl_->publish(channel, log_time_ns, reinterpret_cast<const std::uint8_t*>(text.data()),
                        text.size());
}

std::uint16_t FoxgloveServer::port() const noexcept {
  return impl_->port();
}

std::string FoxgloveServer::url() const {
  return impl_->url();
}

std::size_t FoxgloveServer::clients() const noexcept {
  return impl_->clients();
}

std::vector<ChannelStats> FoxgloveServer::stats() const {
  return impl_->stats();
}

}  // namespace comply::viewer
