#pragma once
// comply.Sim's episode (py_sim.hpp): the controller of either kind as the loop and the gate see it,
// the plant on its simulated clock and the loop. Private to py_sim*.cpp.

#include <cmath>
#include <optional>
#include <variant>

#include "comply/core/clock.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/live_view.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "py_convert.hpp"
#include "py_sim.hpp"

namespace comply::python {

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
      // step()'s info on the simulated clock, the outcome's on the recording's.
      chunk_events.push_back(
          {{timing, record.index, controller.time(), now.nanoseconds()}, record.time_s});
      gate->noteChunk(record.index, timing, controller.time(), now.nanoseconds());
    }
    // The gate's clock is the recording's, so an outcome's applied time is the cycle's.
    gate->noteCycle(record.index, wrapper.controller().idInForce(),
                    [&] { return now.nanoseconds(); });
    if (sampler && record.state != nullptr && (recording != nullptr || view != nullptr)) {
      sampler->fill(record, *record.state, now, sample);
      const auto& in_force = std::get<pipeline::BusOf<Command>>(wrapper.controller().lawBus());
      if (recording != nullptr) {
        recording->cycle<Command>(sample, in_force, record.controller_s, record.start_lateness_s);
      }
      if (view != nullptr) {
        view->cycle<Command>(sample, in_force, record.controller_s, record.start_lateness_s);
      }
    }
  }

  /// Every cycle goes to `to` and is shown on `shown_on` (either null: not there).
  void attach(host::HostRecording* to, host::LiveView* shown_on) {
    recording = to;
    view = shown_on;
    if ((to != nullptr || shown_on != nullptr) && !sampler) {
      sampler.emplace(wrapper);
    }
  }

  /// The recording's clock at the episode's simulated time `t_s`.
  [[nodiscard]] transport::Stamp clockAt(double t_s) const noexcept {
    return transport::Stamp::fromNanoseconds(start_ns + stampNanoseconds(t_s));
  }

  pipeline::Wrapper<Command> wrapper;
  /// A cycle's chunk timing record and the simulated time of that cycle [s].
  struct ChunkEvent {
    pipeline::NotedChunk noted;
    double cycle_s;
  };
  std::vector<ChunkEvent> chunk_events;  // since the last step() took them
  pipeline::CommandGate* gate = nullptr;
  std::int64_t start_ns;  ///< the recording's clock when the episode started
  host::HostRecording* recording = nullptr;
  host::LiveView* view = nullptr;
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

  /// `episode_start_ns`: the recording's clock at the episode's start; `recording`, `view`: null
  /// when there is none (with a view, the plant keeps to real time while a viewer watches).
  Session(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
          std::int64_t episode_start_ns, host::HostRecording* recording, host::LiveView* view)
      : plant(resolved->robot, plantOptions(*resolved)),
        clock(plant),
        gate(pipeline::gateOptions(resolved->config, resolved->cartesian())),
        start_ns(episode_start_ns) {
    if (resolved->cartesian()) {
      episode = std::make_unique<Episode<CartesianCommand>>(resolved, episode_start_ns);
    } else {
      episode = std::make_unique<Episode<JointCommand>>(resolved, episode_start_ns);
    }
    if (view != nullptr) {
      clock.paceWhile(&view->viewingFlag());
    }
    JointState state = JointState::zero(plant.dof());
    plant.read(state);
    std::visit(
        [&](auto& e) {
          e->gate = &gate;
          e->attach(recording, view);
          e->wrapper.activate(state);
          loop = std::make_unique<hardware::ControlLoop>(
              plant, e->wrapper, clock, hardware::LoopOptions{.period_s = plant.controlPeriod()});
          loop->setObserver(e.get());
        },
        episode);
  }

  void detachRecording() {
    std::visit([](auto& e) { e->attach(nullptr, e->view); }, episode);
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
          // The contact reflex (ControllerState's reflex_tripped, reflex_wrench): tripped, and on
          // what (task frame then); while its hold lasts the episode's commands are refused.
          obs["reflex_tripped"] = controller.reflex().tripped();
          obs["reflex_wrench"] = array(controller.reflex().wrench());
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

}  // namespace comply::python
