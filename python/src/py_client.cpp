// comply.Client (see py_client.hpp): connecting, sending and closing; py_client_receive.cpp takes
// what the host sends back.

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
// Commands sent whose round trip is still awaited (the newest; an older one's outcome no longer
// times the clock).
constexpr std::size_t kAwaitedRoundTrips = 64;
// The writers keep every unacknowledged command: a write waits while the commands before it fill
// the writer's history and fails when the host acknowledges none of them within the reliability's
// 0.1 s blocking time.
constexpr const char* kNoHost =
    "no comply host matches this client's writer (comply run stopped, or never there)";
constexpr const char* kRefused =
    "DDS refused the message: the host acknowledged none of the messages sent before it on this "
    "topic within 0.1 s (is comply run stopped or stalled?)";

double secondsUntil(SteadyClock::time_point deadline) {
  return std::chrono::duration<double>(deadline - SteadyClock::now()).count();
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

transport::ParticipantOptions participantOptions(
    int domain, const std::string& network, const std::optional<std::filesystem::path>& security) {
  return {.domain_id = domain,
          .network = network == "all" ? transport::Network::kAll : transport::Network::kLoopback,
          .security = security.value_or(std::filesystem::path())};
}

}  // namespace

Client::Link::Link(const transport::ParticipantOptions& options, const std::string& name)
    : participant(options),
      cartesian(participant, name, transport::kKeepAll),
      joint(participant, name, transport::kKeepAll),
      cartesian_chunk(participant, name, transport::kKeepAll),
      joint_chunk(participant, name, transport::kKeepAll),
      committed_request(participant, name),
      request(participant, name),
      state(participant, name),
      diagnostics(participant, name, 10000),
      committed(participant, name),
      arrivals(participant) {
  arrivals.attach(state);
  arrivals.attach(committed);
}

Client::Client(const std::string& name, int domain, const std::string& network, double timeout_s,
               const std::optional<std::filesystem::path>& record,
               const std::optional<std::filesystem::path>& security)
    : name_(name),
      link_(std::make_unique<Link>(participantOptions(domain, network, security), name)) {
  sender_ = link_->participant.gid();
  if (record) {  // before the first state is taken: that one is recorded too
    recording_ = std::make_unique<ClientRecording>(*record, name, domain, network);
  }
  const auto deadline =
      SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                               std::chrono::duration<double>(std::max(timeout_s, 0.0)));
  bool found = false;
  {
    const py::gil_scoped_release release;
    found = receiveUntil([this] { return state_.has_value(); }, timeout_s, 0.05);
  }
  if (!found) {
    throw py::value_error("no comply host named '" + name + "' on domain " +
                          std::to_string(domain) + " (is `comply run` up?)");
  }
  // No other thread has the client yet.
  dof_ = static_cast<int>(state_->position.size());
  cartesian_ = state_->command_kind == transport::WireCommandKind::kCartesian;
  handshake(secondsUntil(deadline) + 1.0);
}

void Client::handshake(double timeout_s) {
  const py::gil_scoped_release release;
  const auto deadline = SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                                 std::chrono::duration<double>(timeout_s));
  while (SteadyClock::now() < deadline) {
    transport::RequestMessage probe;
    probe.request = transport::RequestType::kProbe;
    {
      const std::lock_guard<std::mutex> sending(sending_);
      probe.header.stamp = nextStamp();
      write(link().request, probe);
    }
    const std::int64_t stamp = probe.header.stamp.nanoseconds();
    if (receiveUntil([&] { return outcomes_.count(stamp) > 0; }, 0.1, 0.02)) {
      return;
    }
  }
  throw std::runtime_error("the host '" + name_ +
                           "' did not account a probe request (a host older than this client "
                           "does not answer one)");
}

Client::Link& Client::link() const {
  if (!link_) {
    throw std::runtime_error("this comply.Client is closed");
  }
  return *link_;
}

template <typename Message>
bool Client::write(transport::Writer<Message>& writer, const Message& message) {
  // Only this client's own commands time a round trip: another sender's stamps are on its clock.
  // Awaited before the write: another thread may take the outcome before write() returns.
  constexpr bool kTimed = !std::is_same_v<Message, transport::RequestMessage>;
  const std::int64_t stamp = message.header.stamp.nanoseconds();
  if constexpr (kTimed) {
    const std::lock_guard<std::mutex> data(data_);
    awaiting_.push_back(stamp);
    if (awaiting_.size() > kAwaitedRoundTrips) {
      awaiting_.pop_front();
    }
  }
  const bool written = writer.write(message);
  const std::lock_guard<std::mutex> data(data_);
  if (!written) {
    if constexpr (kTimed) {
      const auto it = std::find(awaiting_.begin(), awaiting_.end(), stamp);
      if (it != awaiting_.end()) {
        awaiting_.erase(it);
      }
    }
    return false;
  }
  if (recording_) {
    recording_->sent(message);
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

template <typename Command>
Command Client::referenceInForce() const {
  // Keywords a group leaves out keep the reference in force (position alone keeps orientation).
  const std::lock_guard<std::mutex> data(data_);
  return state_ ? transport::referenceInForce<Command>(*state_, dof_) : Command::zero(dof_);
}

template <typename Message>
std::int64_t Client::sendCommand(transport::Writer<Message> Link::*writer,
                                 const py::kwargs& kwargs) {
  using Command = decltype(Message::command);
  // Read with the GIL; stamped and written under sending_ without it, so that the commands of two
  // threads leave in the order of their stamps.
  Message message{{{}, ""}, commandFromKwargs<Command>(kwargs, dof_, referenceInForce<Command>())};
  const py::gil_scoped_release release;
  const std::lock_guard<std::mutex> sending(sending_);
  message.header.stamp = nextStamp();
  publish(link().*writer, message);
  return message.header.stamp.nanoseconds();
}

std::int64_t Client::sendCartesian(const py::kwargs& kwargs) {
  return sendCommand(&Link::cartesian, kwargs);
}

std::int64_t Client::sendJoint(const py::kwargs& kwargs) {
  return sendCommand(&Link::joint, kwargs);
}

std::int64_t Client::sendChunk(const py::object& chunk, const py::object& relative_to,
                               const py::object& keep) {
  std::int64_t offset_ns = 0;
  {
    const std::lock_guard<std::mutex> data(data_);
    const std::optional<ClockSample> best = bestClockSample();
    offset_ns = best ? best->offset_ns : 0;
  }
  const double host_now_s = stampSeconds(transport::Stamp::now().nanoseconds() + offset_ns);
  const double origin_s = relative_to.is_none() ? host_now_s : relative_to.cast<double>();
  const auto send = [&](auto writer, auto message) {  // writer: a member of Link
    using Command = decltype(message.chunk.waypoints[0].command);
    message.chunk =
        chunkFromPython(chunk, dof_, origin_s, std::optional(referenceInForce<Command>()));
    checkWaypointTimes(message.chunk, host_now_s);
    message.chunk.observation_s = origin_s;
    message.chunk.takeover_s = takeoverOfKeep(message.chunk, keep);
    const py::gil_scoped_release release;
    const std::lock_guard<std::mutex> sending(sending_);
    message.header.stamp = nextStamp();
    message.chunk.stamp_s = message.header.stamp.seconds();
    publish(link().*writer, message);
    return message.header.stamp.nanoseconds();
  };
  return cartesian_ ? send(&Link::cartesian_chunk, transport::CartesianChunkMessage{})
                    : send(&Link::joint_chunk, transport::JointChunkMessage{});
}

std::int64_t Client::request(transport::RequestType request) {
  const py::gil_scoped_release release;
  const std::lock_guard<std::mutex> sending(sending_);
  transport::RequestMessage message;
  message.header.stamp = nextStamp();
  message.request = request;
  publish(link().request, message);
  return message.header.stamp.nanoseconds();
}

void Client::close() {
  const py::gil_scoped_release release;
  {
    // No thread sends or reads meanwhile; the participant's writers go with it, which the host
    // sees as the sender gone.
    const std::scoped_lock both(sending_, reading_);
    link_.reset();
  }
  {
    // Every later call sees the client closed and records nothing more...
    const std::scoped_lock all(sending_, reading_, data_);
    closed_ = true;
    if (recording_) {
      recording_->close();
    }
  }
  // ...while the file is finished without a lock: other threads wait on data_ with the GIL held.
  if (recording_) {
    recording_->finish();
  }
  arrived_.notify_all();
}

py::object Client::recordingStats() const {
  return recording_ ? py::object(toDict(recording_->stats())) : py::object(py::none());
}

}  // namespace comply::python
