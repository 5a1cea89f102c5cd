// comply.Client (see py_client.hpp).

#include "py_client.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <type_traits>

#include "py_convert.hpp"

namespace comply::python {
namespace {

using SteadyClock = std::chrono::steady_clock;
constexpr std::size_t kOutcomesKept = 100000;
// Round trips the clock estimate keeps: the one with the least delay of them gives the offset.
constexpr std::size_t kClockSamples = 64;
// The writers keep every unacknowledged command: a write waits while the commands before it fill
// the writer's history and fails when the host acknowledges none of them within the reliability's
// 0.1 s blocking time.
constexpr const char* kNoHost =
    "no comply host matches this client's writer (comply run stopped, or never there)";
constexpr const char* kRefused =
    "DDS refused the message: the host acknowledged none of the messages sent before it on this "
    "topic within 0.1 s (is comply run stopped or stalled?)";

SteadyClock::time_point deadlineAfter(double seconds) {
  return SteadyClock::now() +
         std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}

/// A waypoint time a stamp cannot carry (not finite, or outside int32 seconds) would reach the
/// host as another time: refused before it is sent, in the words the host uses for a chunk it
/// refuses, naming the time as given. `host_now_s`: the host's clock as estimated [s].
template <typename Command>
void checkWaypointTimes(const Chunk<Command>& chunk, double host_now_s) {
  for (std::size_t k = 0; k < chunk.waypoints.size(); ++k) {
    const double time_s = chunk.waypoints[k].time_s;
    const std::string waypoint = "waypoint " + std::to_string(k);
    if (!std::isfinite(time_s)) {
      throw py::value_error("non_finite: " + waypoint + " time is not finite");
    }
    if (!transport::Stamp::holds(time_s)) {
      const double away_s = time_s - host_now_s;
      std::ostringstream text;
      text << std::fixed << std::setprecision(3) << "invalid_chunk: " << waypoint << " at "
           << time_s << " s is due " << std::defaultfloat << std::setprecision(6)
           << std::abs(away_s) << (away_s > 0.0 ? " s ahead of" : " s before")
           << " the host's clock (estimated at " << std::fixed << std::setprecision(3) << host_now_s
           << " s), outside what a stamp holds (int32 seconds: 1901-12-13 to "
           << "2038-01-19)";
      throw py::value_error(text.str());
    }
  }
}

/// Every sample taken, once, at the wall clock when it was taken (a malformed one holds no
/// message to record).
template <typename Message>
void recordTaken(ClientRecording& recording,
                 const std::vector<transport::Sample<Message>>& samples) {
  const transport::Stamp taken = transport::Stamp::now();
  for (const transport::Sample<Message>& sample : samples) {
    if (sample.malformed.empty()) {
      recording.seen(sample.message, taken);
    }
  }
}

}  // namespace

Client::Client(const std::string& name, int domain, const std::string& network, double timeout_s,
               const std::optional<std::filesystem::path>& record,
               const std::optional<std::filesystem::path>& security)
    : name_(name),
      participant_(
          {.domain_id = domain,
           .network = network == "all" ? transport::Network::kAll : transport::Network::kLoopback,
           .security = security.value_or(std::filesystem::path())}),
      sender_(participant_.gid()),
      // A sender faster than the host waits for room instead of losing its oldest command.
      cartesian_writer_(participant_, name, transport::kKeepAll),
      joint_writer_(participant_, name, transport::kKeepAll),
      cartesian_chunk_writer_(participant_, name, transport::kKeepAll),
      joint_chunk_writer_(participant_, name, transport::kKeepAll),
      request_writer_(participant_, name),
      state_reader_(participant_, name),
      diagnostics_reader_(participant_, name, 10000) {
  if (record) {  // before the first state is taken: that one is recorded too
    recording_ = std::make_unique<ClientRecording>(*record, name, domain, network);
  }
  const auto deadline = deadlineAfter(timeout_s);
  {
    const py::gil_scoped_release release;
    while (!state_ && SteadyClock::now() < deadline) {
      poll(0.05);
    }
  }
  if (!state_) {
    throw py::value_error("no comply host named '" + name + "' on domain " +
                          std::to_string(domain) + " (is `comply run` up?)");
  }
  dof_ = static_cast<int>(state_->position.size());
  cartesian_ = state_->command_kind == transport::WireCommandKind::kCartesian;
  handshake(std::chrono::duration<double>(deadline - SteadyClock::now()).count() + 1.0);
}

void Client::handshake(double timeout_s) {
  const py::gil_scoped_release release;
  const auto deadline = deadlineAfter(timeout_s);
  while (SteadyClock::now() < deadline) {
    const transport::Stamp stamp = nextStamp();
    if (cartesian_) {
      transport::CartesianCommandMessage probe{{stamp, ""}, CartesianCommand::zero(dof_)};
      probe.command.fields = CommandField::kNone;
      write(cartesian_writer_, probe);
    } else {
      transport::JointCommandMessage probe{{stamp, ""}, JointCommand::zero(dof_)};
      probe.command.fields = CommandField::kNone;
      write(joint_writer_, probe);
    }
    const auto wait_until = deadlineAfter(0.1);
    while (SteadyClock::now() < wait_until) {
      poll(0.02);
      if (outcomes_.count(stamp.nanoseconds()) > 0) {
        return;
      }
    }
  }
  throw std::runtime_error("the host '" + name_ + "' did not account a probe command");
}

template <typename Message>
bool Client::write(transport::Writer<Message>& writer, const Message& message) {
  if (!writer.write(message)) {
    return false;
  }
  if (recording_) {
    recording_->sent(message);
  }
  if constexpr (!std::is_same_v<Message, transport::RequestMessage>) {
    // Only this client's own commands time a round trip: another sender's stamps are on its clock.
    awaiting_.push_back(message.header.stamp.nanoseconds());
    if (awaiting_.size() > kClockSamples) {
      awaiting_.pop_front();
    }
  }
  return true;
}

template <typename Message>
void Client::publish(transport::Writer<Message>& writer, const Message& message) {
  if (writer.matched() == 0) {
    throw std::runtime_error(kNoHost);  // DDS would drop it without a word
  }
  if (!write(writer, message)) {
    throw std::runtime_error(kRefused);
  }
}

transport::Stamp Client::nextStamp() {
  transport::Stamp now = transport::Stamp::now();
  if (now <= last_stamp_) {
    now = transport::Stamp::fromNanoseconds(last_stamp_.nanoseconds() + 1);
  }
  last_stamp_ = now;
  return now;
}

bool Client::poll(double wait_s) {
  std::vector<transport::Sample<transport::ControllerStateMessage>> states;
  std::vector<transport::Sample<transport::DiagnosticsMessage>> diagnostics;
  if (wait_s > 0.0) {
    state_reader_.wait(wait_s);
  }
  state_reader_.take(states);
  diagnostics_reader_.take(diagnostics, nullptr, 100000);
  if (recording_) {
    recordTaken(*recording_, states);
    recordTaken(*recording_, diagnostics);
  }
  if (!states.empty()) {
    state_ = std::move(states.back().message);
    state_received_ = SteadyClock::now();
  }
  const std::int64_t taken_ns = transport::Stamp::now().nanoseconds();
  for (auto& sample : diagnostics) {
    const std::int64_t published_ns = sample.message.header.stamp.nanoseconds();
    for (const auto& outcome : sample.message.outcomes) {
      if (!transport::sentBy(outcome, sender_)) {
        continue;  // another sender's command, which may carry one of this client's stamps
      }
      const std::int64_t stamp = outcome.stamp.nanoseconds();
      if (outcomes_.emplace(stamp, outcome).second) {
        outcome_order_.push_back(stamp);
        // Sent at `stamp` here, received by the host, published by it, taken here.
        const std::int64_t received_ns = outcome.received.nanoseconds();
        const auto mine = std::find(awaiting_.begin(), awaiting_.end(), stamp);
        if (mine != awaiting_.end() && received_ns > 0) {
          awaiting_.erase(mine);
          clock_samples_.push_back({(taken_ns - stamp) - (published_ns - received_ns),
                                    ((received_ns - stamp) + (published_ns - taken_ns)) / 2});
          if (clock_samples_.size() > kClockSamples) {
            clock_samples_.pop_front();
          }
        }
      }
    }
    sample.message.outcomes.clear();
    diagnostics_ = std::move(sample.message);
    diagnostics_received_ = SteadyClock::now();
  }
  while (outcome_order_.size() > kOutcomesKept) {
    outcomes_.erase(outcome_order_.front());
    outcome_order_.pop_front();
  }
  return !states.empty();
}

template <typename Command>
Command Client::referenceInForce() const {
  // Keywords a group leaves out keep the reference in force (position alone keeps orientation).
  return state_ ? transport::referenceInForce<Command>(*state_, dof_) : Command::zero(dof_);
}

template <typename Message>
std::int64_t Client::sendCommand(transport::Writer<Message>& writer, const py::kwargs& kwargs) {
  using Command = decltype(Message::command);
  Message message{{{}, ""}, commandFromKwargs<Command>(kwargs, dof_, referenceInForce<Command>())};
  message.header.stamp = nextStamp();
  publish(writer, message);
  return message.header.stamp.nanoseconds();
}

std::int64_t Client::sendCartesian(const py::kwargs& kwargs) {
  return sendCommand(cartesian_writer_, kwargs);
}

std::int64_t Client::sendJoint(const py::kwargs& kwargs) {
  return sendCommand(joint_writer_, kwargs);
}

std::int64_t Client::sendChunk(const py::object& chunk, const py::object& relative_to) {
  const transport::Stamp stamp = nextStamp();
  const std::optional<ClockSample> best = bestClockSample();
  const double host_now_s = stampSeconds(stamp.nanoseconds() + (best ? best->offset_ns : 0));
  const double origin_s = relative_to.is_none() ? host_now_s : relative_to.cast<double>();
  const auto send = [&](auto& writer, auto message) {
    using Command = decltype(message.chunk.waypoints[0].command);
    message.header.stamp = stamp;
    message.chunk =
        chunkFromPython(chunk, dof_, origin_s, std::optional(referenceInForce<Command>()));
    checkWaypointTimes(message.chunk, host_now_s);
    message.chunk.stamp_s = stamp.seconds();
    publish(writer, message);
  };
  if (cartesian_) {
    send(cartesian_chunk_writer_, transport::CartesianChunkMessage{});
  } else {
    send(joint_chunk_writer_, transport::JointChunkMessage{});
  }
  return stamp.nanoseconds();
}

std::optional<Client::ClockSample> Client::bestClockSample() const {
  if (clock_samples_.empty()) {
    return std::nullopt;
  }
  return *std::min_element(
      clock_samples_.begin(), clock_samples_.end(),
      [](const ClockSample& a, const ClockSample& b) { return a.delay_ns < b.delay_ns; });
}

py::object Client::clock() const {
  const std::optional<ClockSample> best = bestClockSample();
  if (!best) {
    return py::none();
  }
  py::dict d;
  d["offset"] = 1e-9 * static_cast<double>(best->offset_ns);
  d["round_trip"] = 1e-9 * static_cast<double>(best->delay_ns);
  d["one_way_latency"] = 0.5e-9 * static_cast<double>(best->delay_ns);
  d["samples"] = clock_samples_.size();
  return d;
}

void Client::request(transport::RequestType request) {
  transport::RequestMessage message;
  message.header.stamp = nextStamp();
  message.request = request;
  publish(request_writer_, message);
}

void Client::close() {
  if (recording_) {
    recording_->stop();
  }
}

py::object Client::recordingStats() const {
  return recording_ ? py::object(toDict(recording_->stats())) : py::object(py::none());
}

py::object Client::state(double timeout_s) {
  bool fresh = false;
  {
    const py::gil_scoped_release release;
    const auto deadline = deadlineAfter(timeout_s);
    fresh = poll(0.0);
    while (!fresh && SteadyClock::now() < deadline) {
      fresh = poll(0.01);
    }
  }
  // A host that stopped publishing, or whose writer is gone (a state it sent before it stopped
  // can still be waiting here), is gone or stalled: no state, rather than its last one.
  if (!fresh || !state_ || state_reader_.matched() == 0) {
    return py::none();
  }
  py::dict state = toDict(*state_);
  state["age"] = std::chrono::duration<double>(SteadyClock::now() - state_received_).count();
  return state;
}

py::object Client::diagnostics(double timeout_s) {
  const auto fresh_since = deadlineAfter(-std::max(timeout_s, 0.0));
  const auto fresh = [&] { return diagnostics_ && diagnostics_received_ >= fresh_since; };
  {
    const py::gil_scoped_release release;
    const auto deadline = deadlineAfter(timeout_s);
    do {
      poll(0.01);
    } while (!fresh() && SteadyClock::now() < deadline);
  }
  // As state(): a host that stopped publishing, or whose writer is gone, is gone or stalled.
  if (!fresh() || diagnostics_reader_.matched() == 0) {
    return py::none();
  }
  py::dict diagnostics = toDict(*diagnostics_);
  diagnostics["age"] =
      std::chrono::duration<double>(SteadyClock::now() - diagnostics_received_).count();
  return diagnostics;
}

py::object Client::outcome(std::int64_t stamp, double timeout_s) {
  {
    const py::gil_scoped_release release;
    const auto deadline = deadlineAfter(timeout_s);
    poll(0.0);
    while (outcomes_.count(stamp) == 0 && SteadyClock::now() < deadline) {
      poll(0.01);
    }
  }
  const auto found = outcomes_.find(stamp);
  return found != outcomes_.end() ? py::object(toDict(found->second)) : py::object(py::none());
}

bool Client::waitUntil(const py::function& predicate, double timeout_s) {
  const auto deadline = deadlineAfter(timeout_s);
  while (SteadyClock::now() < deadline) {
    bool fresh = false;
    {
      const py::gil_scoped_release release;
      fresh = poll(0.05);
    }
    if (fresh && predicate(toDict(*state_)).cast<bool>()) {
      return true;
    }
  }
  return false;
}

}  // namespace comply::python
