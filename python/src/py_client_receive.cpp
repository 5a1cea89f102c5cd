// comply.Client (see py_client.hpp): what the host sends back, the state, diagnostics and
// outcomes, taken by whichever thread asks while no other is reading.

#include <algorithm>
#include <chrono>

#include "py_client.hpp"
#include "py_convert.hpp"

namespace comply::python {
namespace {

using SteadyClock = std::chrono::steady_clock;
constexpr std::size_t kOutcomesKept = 100000;
// Answers to committed requests kept for the thread that asked (one each; others' are not kept).
constexpr std::size_t kAnswersKept = 64;
// Round trips the clock estimate keeps: the one with the least delay of them gives the offset.
constexpr std::size_t kClockSamples = 64;

SteadyClock::duration durationOf(double seconds) {
  return std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
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

void Client::checkOpen() const {
  if (closed_) {
    throw std::runtime_error("this comply.Client is closed");
  }
}

bool Client::receiveUntil(const std::function<bool()>& done, double timeout_s, double step_s) {
  const auto deadline = SteadyClock::now() + durationOf(std::max(timeout_s, 0.0));
  double wait_s = 0.0;  // the first look does not wait
  while (true) {
    std::unique_lock<std::mutex> readers(reading_, std::try_to_lock);
    const bool reading = readers.owns_lock();
    if (reading) {
      pollLocked(wait_s);
      readers.unlock();
    }
    std::unique_lock<std::mutex> data(data_);
    checkOpen();
    if (done()) {
      return true;
    }
    const auto left = deadline - SteadyClock::now();
    if (left <= SteadyClock::duration::zero()) {
      return false;
    }
    wait_s = std::min(step_s, std::chrono::duration<double>(left).count());
    if (!reading) {
      // Another thread reads: what it takes is this thread's too, delivered through arrived_.
      arrived_.wait_for(data, durationOf(wait_s));
    }
  }
}

void Client::pollLocked(double wait_s) {
  Link& link = this->link();
  std::vector<transport::Sample<transport::ControllerStateMessage>> states;
  std::vector<transport::Sample<transport::DiagnosticsMessage>> diagnostics;
  std::vector<transport::Sample<transport::CommittedMessage>> answers;
  if (wait_s > 0.0) {
    link.arrivals.wait(wait_s);
  }
  link.state.take(states);
  link.diagnostics.take(diagnostics, nullptr, 100000);
  link.committed.take(answers);
  const bool matched = link.state.matched() > 0;
  const std::int64_t taken_ns = transport::Stamp::now().nanoseconds();
  {
    const std::lock_guard<std::mutex> data(data_);
    host_matched_ = matched;
    if (recording_) {
      recordTaken(*recording_, states);
      recordTaken(*recording_, diagnostics);
    }
    if (!states.empty()) {
      state_ = std::move(states.back().message);
      state_received_ = SteadyClock::now();
      ++states_taken_;
    }
    for (auto& sample : diagnostics) {
      takeOutcomes(sample.message, taken_ns);
      sample.message.outcomes.clear();
      diagnostics_ = std::move(sample.message);
      diagnostics_received_ = SteadyClock::now();
    }
    while (outcome_order_.size() > kOutcomesKept) {
      outcomes_.erase(outcome_order_.front());
      outcome_order_.pop_front();
    }
    takeAnswers(answers);
  }
  arrived_.notify_all();
}

void Client::takeAnswers(std::vector<transport::Sample<transport::CommittedMessage>>& answers) {
  for (auto& sample : answers) {
    const transport::CommittedMessage& answer = sample.message;
    if (!sample.malformed.empty() || !transport::answers(answer, answer.request_stamp, sender_)) {
      continue;  // another client's
    }
    const std::int64_t stamp = answer.request_stamp.nanoseconds();
    if (answers_.emplace(stamp, std::move(sample.message)).second) {
      answer_order_.push_back(stamp);
    }
  }
  while (answer_order_.size() > kAnswersKept) {
    answers_.erase(answer_order_.front());
    answer_order_.pop_front();
  }
}

void Client::takeOutcomes(transport::DiagnosticsMessage& diagnostics, std::int64_t taken_ns) {
  const std::int64_t published_ns = diagnostics.header.stamp.nanoseconds();
  for (const auto& outcome : diagnostics.outcomes) {
    if (!transport::sentBy(outcome, sender_)) {
      continue;  // another sender's command, which may carry one of this client's stamps
    }
    const std::int64_t stamp = outcome.stamp.nanoseconds();
    if (!outcomes_.emplace(stamp, outcome).second) {
      continue;
    }
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

std::optional<Client::ClockSample> Client::bestClockSample() const {
  if (clock_samples_.empty()) {
    return std::nullopt;
  }
  return *std::min_element(
      clock_samples_.begin(), clock_samples_.end(),
      [](const ClockSample& a, const ClockSample& b) { return a.delay_ns < b.delay_ns; });
}

py::object Client::clock() const {
  std::optional<ClockSample> best;
  std::size_t samples = 0;
  {
    const std::lock_guard<std::mutex> data(data_);
    best = bestClockSample();
    samples = clock_samples_.size();
  }
  if (!best) {
    return py::none();
  }
  py::dict d;
  d["offset"] = 1e-9 * static_cast<double>(best->offset_ns);
  d["round_trip"] = 1e-9 * static_cast<double>(best->delay_ns);
  d["one_way_latency"] = 0.5e-9 * static_cast<double>(best->delay_ns);
  d["samples"] = samples;
  return d;
}

py::object Client::state(double timeout_s) {
  std::optional<transport::ControllerStateMessage> fresh;
  double age_s = 0.0;
  {
    const py::gil_scoped_release release;
    std::uint64_t seen = 0;
    {
      const std::lock_guard<std::mutex> data(data_);
      checkOpen();
      seen = states_taken_;  // a state waiting in the reader, not yet taken, is new
    }
    if (receiveUntil([&] { return states_taken_ != seen; }, timeout_s, 0.01)) {
      const std::lock_guard<std::mutex> data(data_);
      // A host that stopped publishing, or whose writer is gone (a state it sent before it
      // stopped can still be waiting here), is gone or stalled: no state, rather than its last.
      if (host_matched_) {
        fresh = state_;
        age_s = std::chrono::duration<double>(SteadyClock::now() - state_received_).count();
      }
    }
  }
  if (!fresh) {
    return py::none();
  }
  py::dict state = toDict(*fresh);
  state["age"] = age_s;
  return state;
}

py::object Client::diagnostics(double timeout_s) {
  const auto fresh_since = SteadyClock::now() - durationOf(std::max(timeout_s, 0.0));
  std::optional<transport::DiagnosticsMessage> newest;
  double age_s = 0.0;
  {
    const py::gil_scoped_release release;
    const auto fresh = [&] { return diagnostics_ && diagnostics_received_ >= fresh_since; };
    if (receiveUntil(fresh, timeout_s, 0.01)) {
      const std::lock_guard<std::mutex> data(data_);
      // As state(): a host that stopped publishing, or whose writer is gone, is gone or stalled.
      if (host_matched_) {
        newest = diagnostics_;
        age_s = std::chrono::duration<double>(SteadyClock::now() - diagnostics_received_).count();
      }
    }
  }
  if (!newest) {
    return py::none();
  }
  py::dict diagnostics = toDict(*newest);
  diagnostics["age"] = age_s;
  return diagnostics;
}

py::object Client::outcome(std::int64_t stamp, double timeout_s) {
  std::optional<transport::CommandOutcomeMessage> found;
  {
    const py::gil_scoped_release release;
    // Copied where it is found, under the lock: the oldest outcomes are dropped as new arrive.
    (void)receiveUntil(
        [&] {
          const auto it = outcomes_.find(stamp);
          if (it != outcomes_.end()) {
            found = it->second;
          }
          return found.has_value();
        },
        timeout_s, 0.01);
  }
  return found ? py::object(toDict(*found)) : py::object(py::none());
}

bool Client::waitUntil(const py::function& predicate, double timeout_s) {
  const auto deadline = SteadyClock::now() + durationOf(std::max(timeout_s, 0.0));
  std::uint64_t seen = 0;
  {
    const std::lock_guard<std::mutex> data(data_);
    checkOpen();
    seen = states_taken_;
  }
  while (SteadyClock::now() < deadline) {
    std::optional<transport::ControllerStateMessage> fresh;
    {
      const py::gil_scoped_release release;
      const double left_s = std::chrono::duration<double>(deadline - SteadyClock::now()).count();
      if (receiveUntil([&] { return states_taken_ != seen; }, left_s, 0.05)) {
        const std::lock_guard<std::mutex> data(data_);
        seen = states_taken_;
        // As state(): a state of a host whose writer is gone is not judged.
        if (host_matched_) {
          fresh = state_;
        }
      }
    }
    if (fresh && predicate(toDict(*fresh)).cast<bool>()) {
      return true;
    }
  }
  return false;
}

}  // namespace comply::python
