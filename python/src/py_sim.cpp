// comply.Sim (see py_sim.hpp).

#include "py_sim.hpp"

#include <cmath>
#include <optional>
#include <variant>

#include "comply/core/clock.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "py_convert.hpp"

namespace comply::python {

/// The episode's controller of either kind, as the loop and the gate see it.
template <typename Command>
struct Episode final : hardware::LoopObserver {
  explicit Episode(const std::shared_ptr<const pipeline::ResolvedController>& resolved)
      : wrapper(resolved) {}
  void afterCycle(const hardware::CycleRecord& record) override {
    gate->noteCycle(record.index, wrapper.controller().stampInForce(), wallClockNanoseconds);
  }
  pipeline::Wrapper<Command> wrapper;
  pipeline::CommandGate* gate = nullptr;
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

  explicit Session(const std::shared_ptr<const pipeline::ResolvedController>& resolved)
      : plant(resolved->robot, plantOptions(*resolved)),
        clock(plant),
        gate(pipeline::gateOptions(resolved->config, resolved->cartesian())) {
    if (resolved->cartesian()) {
      episode = std::make_unique<Episode<CartesianCommand>>(resolved);
    } else {
      episode = std::make_unique<Episode<JointCommand>>(resolved);
    }
    JointState state = JointState::zero(plant.dof());
    plant.read(state);
    std::visit(
        [&](auto& e) {
          e->gate = &gate;
          e->wrapper.activate(state);
          loop = std::make_unique<hardware::ControlLoop>(
              plant, e->wrapper, clock, hardware::LoopOptions{.period_s = plant.controlPeriod()});
          loop->setObserver(e.get());
        },
        episode);
  }

  static sim::PlantOptions plantOptions(const pipeline::ResolvedController& resolved) {
    sim::PlantOptions options;
    options.tip_frame = resolved.config.tip_frame;
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
    addPassivity(
        std::visit([](const auto& e) { return e->wrapper.controller().diagnostics().passivity(); },
                   episode),
        obs);
    return obs;
  }
};

Sim::Sim(const std::string& config, const std::string& robot, int steps_per_action,
         double max_time_s)
    : resolved_(pipeline::resolveController(host::simControllerConfig(robot, "", config))),
      steps_per_action_(steps_per_action),
      max_time_s_(max_time_s) {
  if (steps_per_action < 1) {
    throw py::value_error("steps_per_action must be >= 1");
  }
}

Sim::~Sim() = default;

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
  session_ = std::make_unique<Session>(resolved_);
  return session_->observation();
}

py::tuple Sim::step(const py::object& command) {
  if (!session_) {
    throw std::runtime_error("call reset() before step()");
  }
  py::dict info;
  info["accepted"] = true;
  std::optional<std::int64_t> stamp_ns;
  if (!command.is_none()) {
    const py::dict kwargs = command.cast<py::dict>();
    // Simulated time is the stamp: it grows with every step, so the gate's strict rule holds.
    stamp_ns = std::llround(session_->plant.simTime() * 1e9);
    pipeline::Offer offer;
    offer.stamp_ns = *stamp_ns;
    offer.kind = cartesian() ? pipeline::CommandKind::kCartesian : pipeline::CommandKind::kJoint;
    offer.publisher = 1;  // this process is the only writer
    offer.now_ns = monotonicNanoseconds();
    offer.clock_ns = *stamp_ns;  // the stamps are the simulated clock itself
    std::visit(
        [&](auto& e) {
          using Command = std::remove_cvref_t<decltype(e->wrapper.lastAccepted())>;
          Command c;
          if constexpr (std::is_same_v<Command, CartesianCommand>) {
            c = cartesianFromKwargs(kwargs, dof(), e->wrapper.lastAccepted());
          } else {
            c = jointFromKwargs(kwargs, dof(), e->wrapper.lastAccepted());
          }
          c.stamp_s = stampSeconds(*stamp_ns);
          const bool active = e->wrapper.diagnostics().state != pipeline::WrapperState::kInactive;
          session_->gate.offer(offer, active, [&] { return e->wrapper.submit(c); });
        },
        session_->episode);
  }
  {
    const py::gil_scoped_release release;
    session_->run(steps_per_action_);
  }
  session_->gate.settle();
  for (const pipeline::CommandOutcome& outcome : session_->gate.takeOutcomes()) {
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
  info["state"] = std::string(pipeline::toString(d.state));
  info["last_fault"] = d.last_fault;
  return py::make_tuple(session_->observation(), 0.0, terminated, truncated, info);
}

}  // namespace comply::python
