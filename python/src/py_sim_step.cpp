// comply.Sim's step and what it answers between steps (see py_sim.hpp): a command or chunk offered
// through the gate, the cycles run, the outcomes and the chunks' timing records; the committed
// reference.

#include <cmath>
#include <optional>
#include <string>
#include <variant>

#include "comply/core/clock.hpp"
#include "py_convert.hpp"
#include "py_sim.hpp"
#include "py_sim_session.hpp"

namespace comply::python {

double Sim::lastCycleTime() const noexcept {
  // The observation is taken at the next cycle's start; the last cycle ran one period before.
  return session_->plant.simTime() - session_->plant.controlPeriod();
}

py::dict Sim::committed(double observation_time_s, double dt_s, int count) {
  if (!session_) {
    throw std::runtime_error("call reset() before committed()");
  }
  if (!(dt_s > 0.0) || !std::isfinite(dt_s) || !std::isfinite(observation_time_s) || count < 1) {
    throw py::value_error("committed() needs a finite observation time, dt > 0 and n >= 1");
  }
  std::vector<double> times(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    times[static_cast<std::size_t>(k)] = observation_time_s + k * dt_s;
  }
  return std::visit(
      [&](auto& e) {
        using Command = std::remove_cvref_t<decltype(e->wrapper.lastAccepted())>;
        std::vector<Command> commands;
        const bool known = e->wrapper.predict(times, lastCycleTime(), commands);
        return committedDict(commands, times, known);
      },
      session_->episode);
}

std::optional<std::int64_t> Sim::offer(const py::object& command, const py::object& relative_to,
                                       const py::object& keep) {
  // Simulated time is the stamp: it grows with every step, so the gate's strict rule holds.
  // It is also the observation's time, which a chunk's times are relative to.
  const double now_s = session_->plant.simTime();
  const std::int64_t stamp_ns = stampNanoseconds(now_s);
  pipeline::Offer offer;
  offer.stamp_ns = stamp_ns;
  offer.kind = cartesian() ? pipeline::CommandKind::kCartesian : pipeline::CommandKind::kJoint;
  offer.publisher = 1;  // this process is the only writer
  offer.now_ns = monotonicNanoseconds();
  offer.clock_ns = stamp_ns;  // the stamps are the simulated clock itself
  const bool chunk = isChunk(command);
  std::visit(
      [&](auto& e) {
        using Command = std::remove_cvref_t<decltype(e->wrapper.lastAccepted())>;
        const transport::Header header{transport::Stamp::fromNanoseconds(stamp_ns),
                                       resolved_->robot.base_frame};
        const bool active = e->wrapper.diagnostics().state != pipeline::WrapperState::kInactive;
        if (chunk) {
          const double origin_s = relative_to.is_none() ? now_s : relative_to.cast<double>();
          Chunk<Command> c =
              chunkFromPython<Command>(command, dof(), origin_s, e->wrapper.lastAccepted());
          c.stamp_s = stampSeconds(stamp_ns);
          c.observation_s = origin_s;
          c.takeover_s = takeoverOfKeep(c, keep);
          const transport::ChunkMessageOf<Command> message{header, c};
          if (host::HostRecording* to = recording()) {
            to->received(message, e->clockAt(now_s));
          }
          if (view_) {
            view_->received(message, e->clockAt(now_s));
          }
          session_->gate.offer(offer, active, [&](std::int64_t wire_stamp_ns) {
            // The host's clock at the last cycle: the chunk's times then fall on the cycles
            // that run at them.
            return e->wrapper.submitChunk(c, lastCycleTime(), wire_stamp_ns);
          });
          return;
        }
        const py::dict kwargs = command.cast<py::dict>();
        Command c = commandFromKwargs<Command>(kwargs, dof(), e->wrapper.lastAccepted());
        c.stamp_s = stampSeconds(stamp_ns);
        const transport::CommandMessageOf<Command> message{header, c};
        if (host::HostRecording* to = recording()) {
          to->received(message, e->clockAt(now_s));
        }
        if (view_) {
          view_->received(message, e->clockAt(now_s));
        }
        session_->gate.offer(offer, active, [&](std::int64_t wire_stamp_ns) {
          return e->wrapper.submit(c, wire_stamp_ns);
        });
      },
      session_->episode);
  return stamp_ns;
}

py::list Sim::takeChunkTimings() {
  py::list chunks;
  std::visit(
      [&](auto& e) {
        for (const auto& event : e->chunk_events) {
          chunks.append(toDict(event.noted, event.cycle_s));
        }
        e->chunk_events.clear();
      },
      session_->episode);
  return chunks;
}

py::tuple Sim::step(const py::object& command, const py::object& relative_to,
                    const py::object& keep, const py::object& steps) {
  if (!session_) {
    throw std::runtime_error("call reset() before step()");
  }
  const int cycles = steps.is_none() ? steps_per_action_ : steps.cast<int>();
  if (cycles < 1) {
    throw py::value_error("steps must be >= 1");
  }
  py::dict info;
  info["accepted"] = true;
  std::optional<std::int64_t> stamp_ns;
  if (!command.is_none()) {
    stamp_ns = offer(command, relative_to, keep);
  }
  {
    const py::gil_scoped_release release;
    session_->run(cycles);
  }
  session_->gate.settle();
  for (const pipeline::CommandOutcome& outcome : session_->gate.takeOutcomes()) {
    recordOutcome(outcome);
    if (!stamp_ns || outcome.stamp_ns != *stamp_ns) {
      continue;
    }
    info["accepted"] = outcome.applied;
    info["reason"] = outcome.applied ? "" : std::string(pipeline::toString(outcome.reason));
    info["message"] = outcome.message;
    if (outcome.applied) {
      info["applied_cycle"] = outcome.cycle;
    }
  }
  const pipeline::DiagnosticsSnapshot d =
      std::visit([](auto& e) { return e->wrapper.diagnostics(); }, session_->episode);
  const bool terminated = d.state == pipeline::WrapperState::kFault;
  const bool truncated = max_time_s_ > 0.0 && session_->plant.simTime() >= max_time_s_;
  info["chunks"] = takeChunkTimings();
  info["state"] = std::string(toString(d.state));
  info["last_fault"] = d.last_fault;
  py::dict observation = session_->observation();
  addImages(observation);
  return py::make_tuple(observation, 0.0, terminated, truncated, info);
}

}  // namespace comply::python
