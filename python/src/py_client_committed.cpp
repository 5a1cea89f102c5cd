// comply.Client.committed() (see py_client.hpp): the host's committed reference over the wire, one
// request on /<name>/committed_request and this client's answer to it on /<name>/committed.

#include <Python.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <sstream>

#include "py_client.hpp"
#include "py_convert.hpp"

namespace comply::python {
namespace {

using SteadyClock = std::chrono::steady_clock;
// An answer not back by then is asked for again, with the same stamp: a host's writer that has not
// yet discovered this client's reader (discovery of writers and readers is not ordered) drops it.
constexpr double kAskAgainS = 0.25;

template <typename Command, typename Entry>
py::dict arraysOf(const std::vector<Entry>& entries, bool known) {
  std::vector<Command> commands;
  std::vector<double> times_s;
  commands.reserve(entries.size());
  times_s.reserve(entries.size());
  for (const Entry& entry : entries) {
    commands.push_back(entry.command);
    times_s.push_back(entry.header.stamp.seconds());
  }
  return committedDict(commands, times_s, known);
}

[[noreturn]] void raiseTimeout(const std::string& text) {
  PyErr_SetString(PyExc_TimeoutError, text.c_str());
  throw py::error_already_set();
}

}  // namespace

py::dict Client::committed(double observation_time_s, double dt_s, int count, double timeout_s) {
  if (!transport::Stamp::holds(observation_time_s)) {
    throw py::value_error(
        "committed(): observation_time is not a time a stamp holds (finite, "
        "int32 seconds: 1901-12-13 to 2038-01-19)");
  }
  if (count < 1) {
    throw py::value_error("committed(): n >= 1");
  }
  transport::CommittedRequestMessage request;
  request.observation = transport::Stamp::fromSeconds(observation_time_s);
  request.dt_s = dt_s;  // the host refuses one not finite or not > 0, in its words
  request.count = static_cast<std::uint32_t>(count);
  std::optional<transport::CommittedMessage> answer;
  {
    const py::gil_scoped_release release;
    const auto deadline =
        SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                 std::chrono::duration<double>(std::max(timeout_s, 0.0)));
    bool sent = false;
    while (!answer && (!sent || SteadyClock::now() < deadline)) {
      {
        const std::lock_guard<std::mutex> sending(sending_);
        if (!sent) {
          request.header.stamp = nextStamp();
        }
        if (link().committed_request.matched() == 0) {
          throw std::runtime_error(
              "no comply host reads /" + name_ +
              "/committed_request (comply run stopped, or a host older than this client)");
        }
        link().committed_request.write(request);
        sent = true;
      }
      const std::int64_t stamp = request.header.stamp.nanoseconds();
      const double left_s = std::chrono::duration<double>(deadline - SteadyClock::now()).count();
      (void)receiveUntil(
          [&] {
            const auto it = answers_.find(stamp);
            if (it != answers_.end()) {
              answer = it->second;
            }
            return answer.has_value();
          },
          std::min(left_s, kAskAgainS), 0.01);
    }
  }
  if (!answer) {
    std::ostringstream text;
    text << "committed(): no answer from the host '" << name_ << "' within " << timeout_s
         << " s (is comply run up, and newer than this client?)";
    raiseTimeout(text.str());
  }
  if (!answer->answered) {
    throw py::value_error("committed(): the host refused the request: " + answer->message);
  }
  return answer->command_kind == transport::WireCommandKind::kCartesian
             ? arraysOf<CartesianCommand>(answer->cartesian, answer->known)
             : arraysOf<JointCommand>(answer->joint, answer->known);
}

}  // namespace comply::python
