// The two HostHarness implementations (live_harness.hpp) and the instances of the
// transport-neutral tests.

#include "live_harness.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "comply/host/controller_setup.hpp"
#include "comply/host/live_host.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/transport/in_process.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

/// `comply run` as a child process on a random loopback domain, this process its DDS client. A
/// publisher is a participant with a pair of writers (Cartesian, joint) of its own, as a sending
/// process is: the host's publisher rule holds per sending process.
class DdsHarness final : public HostHarness {
 public:
  void start(const std::string& name) override {
    const int domain = randomDomain();
    domain_ = domain;
    name_ = name;
    std::vector<std::string> args = hostArgs(domain, name);
    if (!config_file_.empty()) {
      args.at(2) = config_file_;  // after "run", "--config"
    }
    if (!record_path_.empty()) {
      args.insert(args.end(), {"--record", record_path_});
    }
    if (duration_s_ > 0.0) {
      args.insert(args.end(), {"--duration", std::to_string(duration_s_)});
    }
    for (const std::string& option : hardware_options_) {
      args.insert(args.end(), {"--hardware-option", option});
    }
    process_ = std::make_unique<Process>(args);
    client_ = std::make_unique<Client>(domain, name);
  }
  bool send(const transport::CartesianCommandMessage& message, int publisher) override {
    return writers_.at(publisher)->cartesian.write(message);
  }
  bool send(const transport::JointCommandMessage& message, int publisher) override {
    return writers_.at(publisher)->joint.write(message);
  }
  bool send(const transport::CartesianChunkMessage& message, int publisher) override {
    return writers_.at(publisher)->chunk.write(message);
  }
  transport::Gid sender(int publisher) override {
    return writers_.at(publisher)->participant.gid();
  }
  bool request(transport::RequestType /*request*/, int /*publisher*/) override {
    return false;  // `comply send --request` is the DDS side's requester (tests/apps)
  }
  bool send(const transport::RequestMessage& /*message*/, int /*publisher*/) override {
    return false;
  }
  std::optional<transport::CommittedMessage> committed(
      const transport::CommittedRequestMessage& request, int publisher,
      std::chrono::milliseconds timeout) override {
    Writers& writers = *writers_.at(publisher);
    const transport::Gid sender = writers.participant.gid();
    const auto deadline = Clock::now() + timeout;
    std::vector<transport::Sample<transport::CommittedMessage>> answers;
    // Sent again while no answer comes: the host's writer may not have discovered this reader
    // yet (discovery of readers and writers is not ordered), and a request is only a question.
    while (Clock::now() < deadline) {
      writers.committed_request.write(request);
      const auto resend = std::min(deadline, Clock::now() + 250ms);
      while (Clock::now() < resend) {
        writers.committed.wait(0.05);
        answers.clear();
        writers.committed.take(answers);
        for (const auto& answer : answers) {
          if (transport::answers(answer.message, request.header.stamp, sender)) {
            return answer.message;
          }
        }
      }
    }
    return std::nullopt;
  }
  void close(int publisher) override { writers_.erase(publisher); }
  std::optional<transport::ControllerStateMessage> state(
      std::chrono::milliseconds timeout) override {
    return client_->state(timeout);
  }
  bool poll(std::chrono::milliseconds timeout, const Done& done) override {
    return client_->poll(timeout, done);
  }
  Outcomes& outcomes() override { return client_->outcomes(); }
  [[nodiscard]] const transport::DiagnosticsMessage& last() const override {
    return client_->last();
  }
  int stop() override {
    if (!process_) {
      return -1;
    }
    if (!exit_code_) {
      process_->signal(SIGTERM);
      exit_code_ = process_->wait(10s);
    }
    return *exit_code_;
  }

 protected:
  bool open(int publisher) override {
    const auto& writers = writers_[publisher] = std::make_unique<Writers>(domain_, name_);
    return writers->cartesian.waitForMatch(1, 10.0) && writers->joint.waitForMatch(1, 10.0) &&
           writers->chunk.waitForMatch(1, 10.0) &&
           writers->committed_request.waitForMatch(1, 10.0) &&
           writers->committed.waitForMatch(1, 10.0);
  }

 private:
  struct Writers {
    Writers(int domain, const std::string& name)
        : participant({domain, transport::Network::kLoopback}),
          cartesian(participant, name),
          joint(participant, name),
          chunk(participant, name),
          committed_request(participant, name),
          committed(participant, name) {}
    transport::Participant participant;
    transport::Writer<transport::CartesianCommandMessage> cartesian;
    transport::Writer<transport::JointCommandMessage> joint;
    transport::Writer<transport::CartesianChunkMessage> chunk;
    transport::Writer<transport::CommittedRequestMessage> committed_request;
    transport::Reader<transport::CommittedMessage> committed;
  };

  std::string name_;
  int domain_ = 0;
  // In this order: the writers go before the client's participant, the host last.
  std::unique_ptr<Process> process_;
  std::unique_ptr<Client> client_;
  std::map<int, std::unique_ptr<Writers>> writers_;
  std::optional<int> exit_code_;
};

/// host::runLiveHost on a thread of this process with transport "in_process", stopped through
/// its stop flag; the clients' end of its bus is this harness. Publishers are the bus's
/// publisher ids. Normal scheduling: a test process gets no SCHED_FIFO.
class InProcessHarness final : public HostHarness {
 public:
  ~InProcessHarness() override { stop(); }

  void start(const std::string& name) override {
    // Before the host starts: the bus lives while either end holds it.
    bus_ = transport::InProcessBus::named(name);
    host::LiveHostOptions options;
    options.config_file = config_file_.empty() ? kHostConfig : config_file_;
    options.robot = "fr3";
    options.sim = true;
    options.hardware = "sim";
    options.transport = "in_process";
    options.name = name;
    options.priority = 0;
    options.record_path = record_path_;
    options.hardware_options = hardware_options_;
    options.duration_s = duration_s_;
    const pipeline::WrapperConfig config =
        host::simControllerConfig(options.robot, "", options.config_file);
    host_ = std::thread([this, options, config] {
      try {
        exit_code_ = host::runLiveHost(options, config, stop_, out_, err_);
      } catch (const std::exception& error) {
        err_ << "runLiveHost threw: " << error.what() << "\n";
        exit_code_ = 1;
      }
    });
  }
  bool send(const transport::CartesianCommandMessage& message, int publisher) override {
    bus_->send(message, static_cast<std::uint64_t>(publisher));
    return true;
  }
  bool send(const transport::JointCommandMessage& message, int publisher) override {
    bus_->send(message, static_cast<std::uint64_t>(publisher));
    return true;
  }
  bool send(const transport::CartesianChunkMessage& message, int publisher) override {
    bus_->send(message, static_cast<std::uint64_t>(publisher));
    return true;
  }
  void close(int publisher) override { bus_->depart(static_cast<std::uint64_t>(publisher)); }
  transport::Gid sender(int publisher) override {
    transport::Gid gid{};  // as the bus names a publisher (in_process.cpp)
    const auto number = static_cast<std::uint64_t>(publisher);
    std::memcpy(gid.data(), &number, sizeof(number));
    return gid;
  }
  bool request(transport::RequestType request, int publisher) override {
    transport::RequestMessage message;
    message.header.stamp = transport::Stamp::now();
    message.request = request;
    return send(message, publisher);
  }
  bool send(const transport::RequestMessage& message, int publisher) override {
    bus_->send(message, static_cast<std::uint64_t>(publisher));
    return true;
  }
  std::optional<transport::CommittedMessage> committed(
      const transport::CommittedRequestMessage& request, int publisher,
      std::chrono::milliseconds timeout) override {
    bus_->send(request, static_cast<std::uint64_t>(publisher));
    std::optional<transport::CommittedMessage> found;
    bus_->waitForCommitted(
        std::chrono::duration<double>(timeout).count(),
        [&](const transport::CommittedMessage& answer) {
          if (transport::answers(answer, request.header.stamp, sender(publisher))) {
            found = answer;
          }
          return found.has_value();
        });
    return found;
  }
  std::optional<transport::ControllerStateMessage> state(
      std::chrono::milliseconds timeout) override {
    const auto deadline = Clock::now() + timeout;
    while (true) {
      if (auto state = bus_->state()) {
        return state;
      }
      if (Clock::now() >= deadline) {
        return std::nullopt;
      }
      std::this_thread::sleep_for(10ms);
    }
  }
  bool poll(std::chrono::milliseconds timeout, const Done& done) override {
    const double timeout_s = std::chrono::duration<double>(timeout).count();
    return bus_->waitForDiagnostics(timeout_s, [&](const transport::DiagnosticsMessage& message) {
      last_ = message;
      for (const auto& outcome : message.outcomes) {
        outcomes_[outcome.stamp.nanoseconds()].push_back(outcome);
      }
      return done(last_);
    });
  }
  Outcomes& outcomes() override { return outcomes_; }
  [[nodiscard]] const transport::DiagnosticsMessage& last() const override { return last_; }
  int stop() override {
    if (host_.joinable()) {
      stop_ = true;
      host_.join();
      // What `comply run` would have printed: its start-up line and summary.
      std::cerr << out_.str() << err_.str();
    }
    return exit_code_;
  }

 protected:
  bool open(int /*publisher*/) override { return true; }  // no discovery in a process

 private:
  std::shared_ptr<transport::InProcessBus> bus_;
  std::atomic<bool> stop_{false};
  std::ostringstream out_;
  std::ostringstream err_;
  int exit_code_ = -1;
  std::thread host_;  // joined by stop(), at the latest in the destructor
  transport::DiagnosticsMessage last_;
  Outcomes outcomes_;
};

/// A no-op command of `Command`'s kind: no field group, so the host accounts it and changes
/// nothing (a joint one to the Cartesian controller is refused as wrong_kind, an outcome too).
template <typename Message>
Message noOp(int dof) {
  Message message;
  message.command = decltype(message.command)::zero(dof);
  message.command.fields = CommandField::kNone;
  return message;
}

}  // namespace

bool HostHarness::connect(int publisher, int dof) {
  return open(publisher) && handshake(noOp<transport::CartesianCommandMessage>(dof), publisher) &&
         handshake(noOp<transport::JointCommandMessage>(dof), publisher);
}

std::optional<transport::ControllerStateMessage> HostHarness::startConnected(
    const std::string& name, int publishers) {
  start(name);
  auto first_state = state(20s);
  if (!first_state) {
    ADD_FAILURE() << "no state from host " << name;
    return std::nullopt;
  }
  const int dof = static_cast<int>(first_state->position.size());
  for (int publisher = 1; publisher <= publishers; ++publisher) {
    if (!connect(publisher, dof)) {
      ADD_FAILURE() << "host " << name << " accounted no probe command of publisher " << publisher;
      return std::nullopt;
    }
  }
  return first_state;
}

bool HostHarness::connectChunks(int publisher) {
  transport::CartesianChunkMessage late;  // one waypoint in 1970: refused as late_chunk
  late.chunk.waypoints.push_back({1.0, CartesianCommand::zero(1)});
  return handshake(late, publisher);
}

/// Sends `probe`, newly stamped, until the host reports its outcome. Over DDS a reader that has
/// not yet discovered a writer drops its first samples: after an outcome it has.
template <typename Message>
bool HostHarness::handshake(Message probe, int publisher) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    probe.header.stamp = transport::Stamp::now();
    send(probe, publisher);
    const std::int64_t stamp = probe.header.stamp.nanoseconds();
    if (poll(100ms, [&](const auto&) { return outcomes().count(stamp) > 0; })) {
      outcomes().clear();
      return true;
    }
  }
  return false;
}

std::unique_ptr<HostHarness> makeHarness(const std::string& transport) {
  if (transport == "dds") {
    return std::make_unique<DdsHarness>();
  }
  if (transport == "in_process") {
    return std::make_unique<InProcessHarness>();
  }
  throw std::invalid_argument("no host harness for transport " + transport);
}

INSTANTIATE_TEST_SUITE_P(Transports, LiveHostOn, ::testing::Values("dds", "in_process"),
                         [](const auto& instance) { return instance.param; });

}  // namespace comply::live_test
