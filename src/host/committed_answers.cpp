// A host's answers to committed requests (see committed_answers.hpp).

#include "comply/host/committed_answers.hpp"

#include <cmath>
#include <sstream>
#include <type_traits>

#include "comply/core/chunk.hpp"
#include "comply/core/clock.hpp"

namespace comply::host {
namespace {

constexpr std::uint32_t kNanosecondsPerSecond = 1'000'000'000U;

std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string nanosecRefusal(const char* field, std::uint32_t nanosec) {
  return std::string(field) + " " + std::to_string(nanosec) + " is out of range (0 to 999999999)";
}

}  // namespace

std::string committedRequestRefusal(
    const transport::Sample<transport::CommittedRequestMessage>& sample) {
  if (!sample.malformed.empty()) {
    return sample.malformed;
  }
  const transport::CommittedRequestMessage& request = sample.message;
  if (request.header.stamp.nanosec >= kNanosecondsPerSecond) {
    return nanosecRefusal("header.stamp.nanosec", request.header.stamp.nanosec);
  }
  if (request.observation.nanosec >= kNanosecondsPerSecond) {
    return nanosecRefusal("observation.nanosec", request.observation.nanosec);
  }
  if (request.observation == transport::Stamp{}) {
    return "observation is not given (all zero): the first time asked for, on the host's clock "
           "(a state's header.stamp)";
  }
  if (!std::isfinite(request.dt_s) || !(request.dt_s > 0.0)) {
    return "dt is " + number(request.dt_s) + ": the step between the times [s] is finite and > 0";
  }
  if (request.count == 0 || request.count > static_cast<std::uint32_t>(kMaxChunkWaypoints)) {
    return "count is " + std::to_string(request.count) + ": 1 to " +
           std::to_string(kMaxChunkWaypoints) + " times (a chunk's most waypoints)";
  }
  // In double first: a step of 1e300 s must not overflow the nanoseconds it is checked in.
  const double span_ns = static_cast<double>(request.count - 1) * request.dt_s * 1e9;
  if (span_ns >
      static_cast<double>(transport::Stamp::kMaxNanoseconds - request.observation.nanoseconds())) {
    return "dt is " + number(request.dt_s) +
           ": the last time asked for, observation + (count - 1) dt, is past what a stamp holds "
           "(2038-01-19)";
  }
  return {};
}

template <typename Command>
const transport::CommittedMessage& CommittedAnswers<Command>::answer(
    const transport::Sample<transport::CommittedRequestMessage>& sample, std::int64_t clock_ns) {
  constexpr bool kCartesian = std::is_same_v<Command, CartesianCommand>;
  transport::CommittedMessage& out = answer_;
  out.header.stamp = transport::Stamp::fromNanoseconds(clock_ns);
  out.header.frame_id = frame_id_;
  out.request_stamp = sample.message.header.stamp;
  out.sender = sample.sender;
  out.command_kind =
      kCartesian ? transport::WireCommandKind::kCartesian : transport::WireCommandKind::kJoint;
  out.cartesian.clear();
  out.joint.clear();
  out.known = false;
  out.message = committedRequestRefusal(sample);
  out.answered = out.message.empty();
  if (!out.answered) {
    return out;
  }
  // The times as stamps, each to the nanosecond from the observation's: what a chunk's waypoints
  // planned on that observation carry.
  const std::size_t count = sample.message.count;
  const std::int64_t observation_ns = sample.message.observation.nanoseconds();
  times_ns_.resize(count);
  times_s_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    times_ns_[k] =
        observation_ns + std::llround(static_cast<double>(k) * sample.message.dt_s * 1e9);
    times_s_[k] = stampSeconds(times_ns_[k]);
  }
  // The host's clock as its intake gives it to a chunk (Wrapper::submitChunk's host_time_s): the
  // same mapping onto the controller's clock.
  out.known = wrapper_.predict(times_s_, stampSeconds(clock_ns), predicted_);
  auto& list = [&]() -> auto& {
    if constexpr (kCartesian) {
      return out.cartesian;
    } else {
      return out.joint;
    }
  }
  ();
  list.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    list[k].header.stamp = transport::Stamp::fromNanoseconds(times_ns_[k]);
    list[k].command = predicted_[k];
    list[k].command.stamp_s = times_s_[k];  // as a reader derives it from the header
  }
  return out;
}

template class CommittedAnswers<CartesianCommand>;
template class CommittedAnswers<JointCommand>;

}  // namespace comply::host
