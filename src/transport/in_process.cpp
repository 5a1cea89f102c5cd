// The in-process host transport (see in_process.hpp).

#include "comply/transport/in_process.hpp"

#include <chrono>
#include <cstring>
#include <map>
#include <string>
#include <utility>

namespace comply::transport {
namespace {

std::chrono::duration<double> seconds(double value) {
  return std::chrono::duration<double>(value > 0.0 ? value : 0.0);
}

class InProcessHostTransport final : public HostTransport {
 public:
  explicit InProcessHostTransport(const HostTransportOptions& options)
      : name_(options.name), bus_(InProcessBus::named(options.name)) {}

  void receive(Inbox& inbox, double timeout_s) override { bus_->receive(inbox, timeout_s); }
  void wake() override { bus_->wake(); }
  void publish(const ControllerStateMessage& state) override { bus_->publish(state); }
  void publish(const DiagnosticsMessage& diagnostics) override { bus_->publish(diagnostics); }
  void publish(const CommittedMessage& answer) override { bus_->publish(answer); }
  bool flush(double /*timeout_s*/) override { return true; }  // delivered when published
  [[nodiscard]] std::string describe() const override {
    return "the in-process bus '" + name_ + "'";
  }

 private:
  std::string name_;
  std::shared_ptr<InProcessBus> bus_;
};

}  // namespace

std::shared_ptr<InProcessBus> InProcessBus::named(const std::string& name) {
  static std::mutex buses_mutex;
  static std::map<std::string, std::weak_ptr<InProcessBus>> buses;
  const std::lock_guard<std::mutex> lock(buses_mutex);
  std::shared_ptr<InProcessBus> bus = buses[name].lock();
  if (!bus) {
    bus = std::make_shared<InProcessBus>();
    buses[name] = bus;
  }
  return bus;
}

template <typename Message>
void InProcessBus::post(std::vector<Sample<Message>>& list, const Message& message,
                        std::uint64_t publisher) {
  // One publisher is one process here: its number is its participant and names it as a sender.
  Gid sender{};
  std::memcpy(sender.data(), &publisher, sizeof(publisher));
  Sample<Message> sample{message, publisher, {}, publisher, sender};
  // Held to the bound a DDS reader holds it to: refused, the text not kept.
  if (std::string refusal = frameIdRefusal("header.frame_id", message.header.frame_id.size());
      !refusal.empty()) {
    sample.message.header.frame_id = std::string();
    sample.refuse(Reason::kTooLarge, std::move(refusal));
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    list.push_back(std::move(sample));
  }
  host_wakeup_.notify_all();
}

void InProcessBus::send(const CartesianCommandMessage& message, std::uint64_t publisher) {
  post(inbox_.cartesian, message, publisher);
}

void InProcessBus::send(const JointCommandMessage& message, std::uint64_t publisher) {
  post(inbox_.joint, message, publisher);
}

void InProcessBus::send(const CartesianChunkMessage& message, std::uint64_t publisher) {
  post(inbox_.cartesian_chunks, message, publisher);
}

void InProcessBus::send(const JointChunkMessage& message, std::uint64_t publisher) {
  post(inbox_.joint_chunks, message, publisher);
}

void InProcessBus::send(const RequestMessage& message, std::uint64_t publisher) {
  post(inbox_.requests, message, publisher);
}

void InProcessBus::send(const CommittedRequestMessage& message, std::uint64_t publisher) {
  post(inbox_.committed_requests, message, publisher);
}

void InProcessBus::depart(std::uint64_t publisher) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    inbox_.departed.push_back(publisher);
  }
  host_wakeup_.notify_all();
}

std::optional<ControllerStateMessage> InProcessBus::state() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return state_;
}

bool InProcessBus::waitForDiagnostics(double timeout_s,
                                      const std::function<bool(const DiagnosticsMessage&)>& done) {
  return waitFor(diagnostics_, timeout_s, done);
}

bool InProcessBus::waitForCommitted(double timeout_s,
                                    const std::function<bool(const CommittedMessage&)>& done) {
  return waitFor(committed_, timeout_s, done);
}

template <typename Message>
bool InProcessBus::waitFor(std::deque<Message>& published, double timeout_s,
                           const std::function<bool(const Message&)>& done) {
  const auto deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(seconds(timeout_s));
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    while (!published.empty()) {
      const Message message = std::move(published.front());
      published.pop_front();
      lock.unlock();
      const bool held = done(message);
      lock.lock();
      if (held) {
        return true;
      }
    }
    if (client_wakeup_.wait_until(lock, deadline) == std::cv_status::timeout && published.empty()) {
      return false;
    }
  }
}

void InProcessBus::receive(Inbox& inbox, double timeout_s) {
  std::unique_lock<std::mutex> lock(mutex_);
  host_wakeup_.wait_for(lock, seconds(timeout_s), [&] { return !inbox_.empty() || woken_; });
  woken_ = false;
  const auto move_into = [](auto& from, auto& to) {
    for (auto& sample : from) {
      to.push_back(std::move(sample));
    }
  };
  move_into(inbox_.cartesian, inbox.cartesian);
  move_into(inbox_.joint, inbox.joint);
  move_into(inbox_.cartesian_chunks, inbox.cartesian_chunks);
  move_into(inbox_.joint_chunks, inbox.joint_chunks);
  move_into(inbox_.requests, inbox.requests);
  move_into(inbox_.committed_requests, inbox.committed_requests);
  inbox.departed.insert(inbox.departed.end(), inbox_.departed.begin(), inbox_.departed.end());
  inbox_.clear();
}

void InProcessBus::wake() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    woken_ = true;
  }
  host_wakeup_.notify_all();
}

void InProcessBus::publish(const ControllerStateMessage& state) {
  const std::lock_guard<std::mutex> lock(mutex_);
  state_ = state;
}

void InProcessBus::publish(const DiagnosticsMessage& diagnostics) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    diagnostics_.push_back(diagnostics);
  }
  client_wakeup_.notify_all();
}

void InProcessBus::publish(const CommittedMessage& answer) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    committed_.push_back(answer);
  }
  client_wakeup_.notify_all();
}

std::unique_ptr<HostTransport> makeInProcessHostTransport(const HostTransportOptions& options) {
  return std::make_unique<InProcessHostTransport>(options);
}

}  // namespace comply::transport
