// RTDE over TCP for the UR controller emulator (see rtde_server.hpp).

#include "comply/ur/rtde_server.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "comply/core/realtime_scheduling.hpp"
#include "comply/hardware/loop_clock.hpp"

namespace comply::ur {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

/// Counts the input packages of all clients, for a thread that waits for the next one.
class InputSignal {
 public:
  void notify() {
    {
      const std::lock_guard lock(mutex_);
      ++count_;
    }
    changed_.notify_all();
  }
  /// When a data package last left for a client (monotonic seconds): its write completed.
  void noteOutputWritten() {
    output_written_s_.store(hardware::monotonicSeconds(), std::memory_order_relaxed);
  }
  double outputWritten() const { return output_written_s_.load(std::memory_order_relaxed); }
  std::uint64_t count() const {
    const std::lock_guard lock(mutex_);
    return count_;
  }
  bool awaitAfter(std::uint64_t seen, double timeout_s) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                             [&] { return count_ > seen; });
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t count_ = 0;
  std::atomic<double> output_written_s_{0.0};
};

/// Which client writes which input: one at a time, as on a controller. A leaf lock: nothing is
/// locked while it is held.
class InputOwners {
 public:
  std::set<std::string> takenExcept(const void* client) const {
    const std::lock_guard lock(mutex_);
    std::set<std::string> taken;
    for (const auto& [owner, names] : owners_) {
      if (owner != client) {
        taken.insert(names.begin(), names.end());
      }
    }
    return taken;
  }
  void set(const void* client, std::set<std::string> names) {
    const std::lock_guard lock(mutex_);
    owners_[client] = std::move(names);
  }
  void release(const void* client) {
    const std::lock_guard lock(mutex_);
    owners_.erase(client);
  }

 private:
  mutable std::mutex mutex_;
  std::map<const void*, std::set<std::string>> owners_;
};

/// One client: its socket, its session, what waits to be written.
class Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(tcp::socket socket, const RtdeServerOptions& options, InputSignal& inputs,
             InputOwners& owners)
      : inputs_signal_(inputs),
        owners_(owners),
        socket_(std::move(socket)),
        session_(options.version, options.max_frequency_hz),
        max_frequency_hz_(options.max_frequency_hz) {
    socket_.set_option(tcp::no_delay(true));
  }

  void start() { read(); }
  void close() {
    boost::system::error_code ignored;
    socket_.close(ignored);
  }
  [[nodiscard]] bool open() {
    const std::lock_guard lock(mutex_);
    return open_;
  }

  /// A controller cycle's variables: this client's output recipe when it is due.
  void cycle(const std::map<std::string, RtdeValue>& variables) {
    const std::lock_guard lock(mutex_);
    const std::optional<OutputRecipe>& recipe = session_.output();
    if (!open_ || !session_.started() || !recipe) {
      return;
    }
    // A recipe at a fraction of the controller's rate gets every n-th cycle.
    const auto every = std::max<long>(1, std::lround(max_frequency_hz_ / recipe->frequency_hz));
    if (cycles_++ % every != 0) {
      return;
    }
    std::vector<RtdeValue> values;
    for (std::size_t i = 0; i < recipe->names.size(); ++i) {
      const auto found = variables.find(recipe->names[i]);
      values.push_back(found != variables.end() && typeOf(found->second) == recipe->types[i]
                           ? found->second
                           : zeroOf(recipe->types[i]));
    }
    queueLocked(session_.outputPackage(values));
  }

  void collectInputs(std::map<std::string, RtdeValue>& into) {
    const std::lock_guard lock(mutex_);
    for (const auto& [name, value] : session_.inputs()) {
      into[name] = value;
    }
  }

 private:
  void read() {
    socket_.async_read_some(
        asio::buffer(buffer_),
        [self = shared_from_this()](boost::system::error_code error, std::size_t size) {
          if (error) {
            self->owners_.release(self.get());  // its inputs are free for the next client
            const std::lock_guard lock(self->mutex_);
            self->open_ = false;
            return;
          }
          self->take(size);
          self->read();
        });
  }

  void take(std::size_t size) {
    const std::lock_guard lock(mutex_);
    framer_.feed(std::span(buffer_.data(), size));
    try {
      for (Package package; framer_.next(package);) {
        if (package.type == PackageType::kStart) {
          cycles_ = 0;  // a recipe started anew is served from its first cycle
        }
        if (package.type == PackageType::kSetupInputs) {
          session_.setInputsTakenElsewhere(owners_.takenExcept(this));
        }
        for (std::vector<std::uint8_t>& answer : session_.handle(package)) {
          queueLocked(std::move(answer));
        }
        if (package.type == PackageType::kDataPackage) {
          inputs_signal_.notify();
        }
        if (package.type == PackageType::kSetupInputs) {
          owners_.set(this, session_.inputNames());
        }
      }
    } catch (const RtdeError&) {
      close();  // the stream lost its framing: nothing more can be read from it
    }
  }

  void queueLocked(std::vector<std::uint8_t> bytes) {
    pending_.push_back(std::move(bytes));
    if (!writing_) {
      writing_ = true;
      asio::post(socket_.get_executor(), [self = shared_from_this()] { self->writeNext(); });
    }
  }

  void writeNext() {
    {
      const std::lock_guard lock(mutex_);
      if (pending_.empty() || !open_) {
        writing_ = false;
        return;
      }
      current_ = std::move(pending_.front());
      pending_.pop_front();
    }
    asio::async_write(
        socket_, asio::buffer(current_),
        [self = shared_from_this()](boost::system::error_code error, std::size_t) {
          if (error) {
            const std::lock_guard lock(self->mutex_);
            self->open_ = false;
            self->writing_ = false;
            return;
          }
          if (self->current_.size() > 2 &&
              self->current_[2] == static_cast<std::uint8_t>(PackageType::kDataPackage)) {
            self->inputs_signal_.noteOutputWritten();
          }
          self->writeNext();
        });
  }

  InputSignal& inputs_signal_;
  InputOwners& owners_;
  tcp::socket socket_;
  std::mutex mutex_;  // the emulator's thread and the I/O thread
  RtdeServerSession session_;
  PackageFramer framer_;
  double max_frequency_hz_;
  std::uint64_t cycles_ = 0;
  bool open_ = true;
  bool writing_ = false;
  std::deque<std::vector<std::uint8_t>> pending_;
  std::vector<std::uint8_t> current_;
  std::array<std::uint8_t, 4096> buffer_{};
};

}  // namespace

class RtdeServer::Impl {
 public:
  explicit Impl(const RtdeServerOptions& options) : options_(options), acceptor_(io_) {
    boost::system::error_code error;
    const auto address = asio::ip::make_address(options.address, error);
    const tcp::endpoint endpoint(address, options.port);
    if (!error) {
      acceptor_.open(endpoint.protocol(), error);
    }
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
      throw RtdeError("the RTDE server cannot listen on " + options.address + ":" +
                      std::to_string(options.port) + ": " + error.message());
    }
    accept();
    thread_ = std::thread([this] {
      (void)makeThreadRealtime(options_.thread_priority);  // normal priority where it may not
      io_.run();
    });
  }

  ~Impl() {
    asio::post(io_, [this] {
      stopping_ = true;
      boost::system::error_code ignored;
      acceptor_.close(ignored);
      const std::lock_guard lock(mutex_);
      for (const auto& connection : connections_) {
        connection->close();
      }
    });
    thread_.join();
    connections_.clear();  // their sockets go while the I/O context they belong to is there
  }

  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }

  void sendOutputs(const std::map<std::string, RtdeValue>& variables) {
    const std::lock_guard lock(mutex_);
    std::erase_if(connections_, [](const auto& connection) { return !connection->open(); });
    for (const auto& connection : connections_) {
      connection->cycle(variables);
    }
  }

  std::map<std::string, RtdeValue> inputs() const {
    const std::lock_guard lock(mutex_);
    std::map<std::string, RtdeValue> all;
    for (const auto& connection : connections_) {
      connection->collectInputs(all);
    }
    return all;
  }

  std::uint64_t inputPackages() const { return inputs_signal_.count(); }
  double lastOutputWritten() const { return inputs_signal_.outputWritten(); }
  bool awaitInputs(std::uint64_t seen, double timeout_s) {
    return inputs_signal_.awaitAfter(seen, timeout_s);
  }

  void closeConnections() {
    asio::post(io_, [this] {
      const std::lock_guard lock(mutex_);
      for (const auto& connection : connections_) {
        connection->close();
      }
    });
  }

  std::size_t connections() const {
    const std::lock_guard lock(mutex_);
    return static_cast<std::size_t>(std::count_if(connections_.begin(), connections_.end(),
                                                  [](const auto& c) { return c->open(); }));
  }

 private:
  void accept() {
    acceptor_.async_accept([this](boost::system::error_code error, tcp::socket socket) {
      if (stopping_ || error == asio::error::operation_aborted) {
        return;
      }
      if (!error) {
        auto connection = std::make_shared<Connection>(std::move(socket), options_, inputs_signal_,
                                                       input_owners_);
        {
          const std::lock_guard lock(mutex_);
          connections_.push_back(connection);
        }
        connection->start();
      }
      accept();
    });
  }

  RtdeServerOptions options_;
  InputSignal inputs_signal_;  // before the connections, which hold it
  InputOwners input_owners_;   // so
  mutable std::mutex mutex_;   // the connections' list
  std::vector<std::shared_ptr<Connection>> connections_;
  asio::io_context io_;
  tcp::acceptor acceptor_;
  bool stopping_ = false;  // the I/O thread's
  std::thread thread_;
};

RtdeServer::RtdeServer(const RtdeServerOptions& options) : impl_(std::make_unique<Impl>(options)) {}
RtdeServer::~RtdeServer() = default;
std::uint16_t RtdeServer::port() const noexcept {
  return impl_->port();
}
void RtdeServer::sendOutputs(const std::map<std::string, RtdeValue>& variables) {
  impl_->sendOutputs(variables);
}
std::map<std::string, RtdeValue> RtdeServer::inputs() const {
  return impl_->inputs();
}
double RtdeServer::lastOutputWritten() const {
  return impl_->lastOutputWritten();
}
std::uint64_t RtdeServer::inputPackages() const {
  return impl_->inputPackages();
}
bool RtdeServer::awaitInputs(std::uint64_t seen, double timeout_s) {
  return impl_->awaitInputs(seen, timeout_s);
}
void RtdeServer::closeConnections() {
  impl_->closeConnections();
}
std::size_t RtdeServer::connections() const {
  return impl_->connections();
}

}  // namespace comply::ur
