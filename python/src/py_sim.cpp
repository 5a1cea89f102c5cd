// comply.Sim (see py_sim.hpp).

#include "py_sim.hpp"

#include <cmath>
#include <optional>
#include <variant>

#include "comply/core/clock.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "py_convert.hpp"

namespace comply::python {
namespace {

/// The gate's outcome on the recording's clock: the Sim's commands are received at the simulated
/// time they are stamped with (the gate itself notes the wall clock).
transport::CommandOutcomeMessage simOutcomeMessage(const pipeline::CommandOutcome& outcome,
                                                   std::int64_t episode_start_ns) {
  transport::CommandOutcomeMessage message = host::outcomeMessage(outcome);
  message.received = transport::Stamp::fromNanoseconds(episode_start_ns + outcome.stamp_ns);
  return message;
}

}  // namespace

/// The episode's controller of either kind, as the loop and the gate see it, and its recording.
template <typename Command>
struct Episode final : hardware::LoopObserver {
  Episode(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
          std::int64_t episode_start_ns)
      : wrapper(resolved), start_ns(episode_start_ns) {}

  void afterCycle(const hardware::CycleRecord& record) override {
    const transport::Stamp now = clockAt(record.time_s);
    const pipeline::Controller& controller = wrapper.controller();
    for (const pipeline::ChunkTiming& timing : controller.chunks().events()) {
      chunk_events.push_back({timing, controller.time() - record.time_s, record.index});
      gate->noteChunk(record.index, timing, controller.time(), now.nanoseconds());
    }
    // The gate's clock is the recording's, so an outcome's applied time is the cycle's.
    gate->noteCycle(record.index, wrapper.controller().idInForce(),
                    [&] { return now.nanoseconds(); });
    if (recording != nullptr && record.state != nullptr) {
      sampler->fill(record, *record.state, now, sample);
      recording->cycle<Command>(sample,
                                std::get<pipeline::BusOf<Command>>(wrapper.controller().lawBus()),
                                record.controller_s, record.start_lateness_s);
    }
  }

  void attach(host::HostRecording* to) {
    recording = to;
    if (to != nullptr && !sampler) {
      sampler.emplace(wrapper);
    }
  }

  /// The recording's clock at the episode's simulated time `t_s`.
  [[nodiscard]] transport::Stamp clockAt(double t_s) const noexcept {
    return transport::Stamp::fromNanoseconds(start_ns + stampNanoseconds(t_s));
  }

  /// A chunk's timing record, with the offset of the controller's clock from the simulated one
  /// in its cycle and that cycle's index.
  struct ChunkEvent {
    pipeline::ChunkTiming timing;
    double controller_minus_host_s;
    std::uint64_t cycle;
  };

  pipeline::Wrapper<Command> wrapper;
  std::vector<ChunkEvent> chunk_events;  // since the last step() took them
  pipeline::CommandGate* gate = nullptr;
  std::int64_t start_ns;  ///< the recording's clock when the episode started
  host::HostRecording* recording = nullptr;
  std::optional<host::StateSampler<Command>> sampler;
  host::StateSample sample;  // the loop's scratch
};

/// One episode: the plant on its simulated clock, the controller, the control loop and the gate
/// every command goes through (as in every other host).
struct Sim::Session {
  sim::SimulatedRobot plant;
  sim::SimulatedClock clock;
  std::variant<std::unique_ptr<Episode<CartesianCommand>>, std::unique_ptr<Episode<JointCommand>>>
      episode;
  pipeline::CommandGate gate;
  std::unique_ptr<hardware::ControlLoop> loop;
  std::int64_t start_ns;

  /// `episode_start_ns`: the recording's clock at the episode's start; `recording`: null when
  /// there is none.
  Session(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
          std::int64_t episode_start_ns, host::HostRecording* recording)
      : plant(resolved->robot, plantOptions(*resolved)),
        clock(plant),
        gate(pipeline::gateOptions(resolved->config, resolved->cartesian())),
        start_ns(episode_start_ns) {
    if (resolved->cartesian()) {
      episode = std::make_unique<Episode<CartesianCommand>>(resolved, episode_start_ns);
    } else {
      episode = std::make_unique<Episode<JointCommand>>(resolved, episode_start_ns);
    }
    JointState state = JointState::zero(plant.dof());
    plant.read(state);
    std::visit(
        [&](auto& e) {
          e->gate = &gate;
          e->attach(recording);
          e->wrapper.activate(state);
          loop = std::make_unique<hardware::ControlLoop>(
              plant, e->wrapper, clock, hardware::LoopOptions{.period_s = plant.controlPeriod()});
          loop->setObserver(e.get());
        },
        episode);
  }

  void detachRecording() {
    std::visit([](auto& e) { e->attach(nullptr); }, episode);
  }

  /// The recording's clock now: where the next episode starts.
  [[nodiscard]] std::int64_t clockNs() const noexcept {
    return start_ns + stampNanoseconds(plant.simTime());
  }

  static sim::PlantOptions plantOptions(const pipeline::ResolvedController& resolved) {
    sim::PlantOptions options;
    options.tip_frame = resolved.config.tip_frame;
    options.actuation = resolved.parameters.output.mode;  // the drives the controller drives
    return options;
  }

  /// `cycles` control cycles, then the plant advanced to the next cycle's start, so that the
  /// observation shows the effect of the last torque.
  void run(int cycles) {
    for (int i = 0; i < cycles; ++i) {
      loop->runOnce();
    }
    clock.waitUntil(loop->nextCycleTime());
  }

  py::dict observation() {
    JointState state = JointState::zero(plant.dof());
    plant.read(state);
    py::dict obs;
    obs["time"] = plant.simTime();
    obs["position"] = array(state.position);
    obs["velocity"] = array(state.velocity);
    obs["effort"] = array(state.effort);
    const std::span<const double> torque = loop->lastTorque();
    obs["torque_command"] = array(
        Eigen::Map<const Eigen::VectorXd>(torque.data(), static_cast<Eigen::Index>(torque.size())));
    const Eigen::Isometry3d tcp = plant.tcpPose();
    const Eigen::Vector3d p = tcp.translation();
    const Eigen::Quaterniond q(tcp.linear());
    obs["tcp_position"] = array(p);
    obs["tcp_orientation"] = array(q.coeffs());  // Eigen stores x y z w
    obs["contact_wrench"] = array(plant.toolContactWrench());
    // The reference the law used this cycle (a chunk's point on its curve), as the state's
    // reference_* fields carry it.
    std::visit(
        [&](const auto& e) {
          const auto& bus =
              std::get<pipeline::BusOf<std::remove_cvref_t<decltype(e->wrapper.lastAccepted())>>>(
                  e->wrapper.controller().lawBus());
          // The wrist sensor as the cycle compensated it (the declared tool's weight and the
          // tare off), beside the simulator's own contact wrench.
          const pipeline::Controller& controller = e->wrapper.controller();
          obs["sensor_wrench"] =
              array(controller.sensorWrenchValid() ? controller.sensorWrench() : Vector6d::Zero());
          if constexpr (requires { bus.orientation; }) {
            obs["reference_position"] = array(bus.position, 3);
            obs["reference_orientation"] = array(bus.orientation, 4);
          } else {
            obs["reference_joint_position"] =
                array(bus.position, static_cast<std::size_t>(plant.dof()));
          }
        },
        episode);
    addPassivity(
        std::visit([](const auto& e) { return e->wrapper.controller().diagnostics().passivity(); },
                   episode),
        obs);
    return obs;
  }
};

Sim::Sim(const std::string& config, const std::string& robot, int steps_per_action,
         double max_time_s, const std::optional<std::filesystem::path>& record)
    : resolved_(pipeline::resolveController(host::simControllerConfig(robot, "", config))),
      steps_per_action_(steps_per_action),
      max_time_s_(max_time_s) {
  if (steps_per_action < 1) {
    throw py::value_error("steps_per_action must be >= 1");
  }
  if (record) {
    recording_ = std::make_unique<host::HostRecording>(
        record->string(), resolved_, "comply",
        record::StringMap{{"host", "comply.Sim"},
                          {"clock", "simulated"},
                          {"steps_per_action", std::to_string(steps_per_action)}},
        // Simulated time has no deadline: a step waits for a busy disk, no cycle is lost.
        host::HostRecordingOptions{.when_full = record::WhenFull::kWait});
    recording_open_ = true;
  }
}

Sim::~Sim() {
  close();
}

host::HostRecording* Sim::recording() const noexcept {
  return recording_open_ ? recording_.get() : nullptr;
}

void Sim::close() {
  if (!recording_open_) {
    return;
  }
  if (session_) {
    session_->detachRecording();
  }
  recording_->stop();
  recording_open_ = false;
}

py::object Sim::recordingStats() const {
  return recording_ ? py::object(toDict(recording_->stats())) : py::object(py::none());
}

void Sim::recordOutcome(const pipeline::CommandOutcome& outcome) {
  if (host::HostRecording* to = recording()) {
    to->outcome(simOutcomeMessage(outcome, session_->start_ns));
  }
}

void Sim::endEpisode() {
  if (!session_) {
    return;
  }
  session_->gate.abandonPending("the episode ended before a cycle took the command");
  for (const pipeline::CommandOutcome& outcome : session_->gate.takeOutcomes()) {
    recordOutcome(outcome);
  }
}

int Sim::dof() const noexcept {
  return resolved_->dof;
}

bool Sim::cartesian() const noexcept {
  return resolved_->cartesian();
}

double Sim::time() const noexcept {
  return session_ ? session_->plant.simTime() : 0.0;
}

py::dict Sim::reset() {
  std::int64_t start_ns = 0;
  if (session_) {
    endEpisode();
    start_ns = session_->clockNs();
    session_.reset();
  }
  session_ = std::make_unique<Session>(resolved_, start_ns, recording());
  return session_->observation();
}

void Sim::tare() {
  if (!session_) {
    throw std::runtime_error("call reset() before tare()");
  }
  const std::string why =
      std::visit([](auto& episode) { return episode->wrapper.tare(); }, session_->episode);
  if (!why.empty()) {
    throw std::runtime_error("tare: " + why);
  }
}

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
        py::dict d = toArrays(commands);
        d["time"] = array(times);
        d["known"] = known;
        return d;
      },
      session_->episode);
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
    // Simulated time is the stamp: it grows with every step, so the gate's strict rule holds.
    // It is also the observation's time, which a chunk's times are relative to.
    const double now_s = session_->plant.simTime();
    stamp_ns = stampNanoseconds(now_s);
    pipeline::Offer offer;
    offer.stamp_ns = *stamp_ns;
    offer.kind = cartesian() ? pipeline::CommandKind::kCartesian : pipeline::CommandKind::kJoint;
    offer.publisher = 1;  // this process is the only writer
    offer.now_ns = monotonicNanoseconds();
    offer.clock_ns = *stamp_ns;  // the stamps are the simulated clock itself
    const bool chunk = isChunk(command);
    std::visit(
        [&](auto& e) {
          using Command = std::remove_cvref_t<decltype(e->wrapper.lastAccepted())>;
          const transport::Header header{transport::Stamp::fromNanoseconds(*stamp_ns),
                                         resolved_->robot.base_frame};
          const bool active = e->wrapper.diagnostics().state != pipeline::WrapperState::kInactive;
          if (chunk) {
            const double origin_s = relative_to.is_none() ? now_s : relative_to.cast<double>();
            Chunk<Command> c =
                chunkFromPython<Command>(command, dof(), origin_s, e->wrapper.lastAccepted());
            c.stamp_s = stampSeconds(*stamp_ns);
            c.observation_s = origin_s;
            if (!keep.is_none()) {
              const int m = keep.cast<int>();
              if (m < 0 || m >= static_cast<int>(c.waypoints.size())) {
                throw py::value_error("keep=" + std::to_string(m) + ": a chunk of " +
                                      std::to_string(c.waypoints.size()) +
                                      " waypoints takes over at one of them (0 to " +
                                      std::to_string(c.waypoints.size() - 1) + ")");
              }
              c.takeover_s = c.waypoints[static_cast<std::size_t>(m)].time_s;
            }
            if (host::HostRecording* to = recording()) {
              to->received(transport::ChunkMessageOf<Command>{header, c},
                           e->clockAt(session_->plant.simTime()));
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
          c.stamp_s = stampSeconds(*stamp_ns);
          if (host::HostRecording* to = recording()) {
            to->received(transport::CommandMessageOf<Command>{header, c},
                         e->clockAt(session_->plant.simTime()));
          }
          session_->gate.offer(offer, active, [&](std::int64_t wire_stamp_ns) {
            return e->wrapper.submit(c, wire_stamp_ns);
          });
        },
        session_->episode);
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
  py::list chunks;
  std::visit(
      [&](auto& e) {
        for (const auto& event : e->chunk_events) {
          chunks.append(toDict(event.timing, event.controller_minus_host_s, event.cycle));
        }
        e->chunk_events.clear();
      },
      session_->episode);
  info["chunks"] = chunks;
  info["state"] = std::string(toString(d.state));
  info["last_fault"] = d.last_fault;
  return py::make_tuple(session_->observation(), 0.0, terminated, truncated, info);
}

}  // namespace comply::python
