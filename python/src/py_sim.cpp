// comply.Sim (see py_sim.hpp).

#include "py_sim.hpp"

#include <variant>

#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/host/controller_setup.hpp"
#include "py_convert.hpp"

namespace comply::python {

/// One episode: the plant and the wrapper of the controller's kind.
struct Sim::Session {
  sim::SimulatedRobot plant;
  std::variant<std::unique_ptr<pipeline::CartesianWrapper>, std::unique_ptr<pipeline::JointWrapper>>
      wrapper;
  JointState state;
  JointVector torque;
  bool wrote = false;

  Session(const std::shared_ptr<const pipeline::ResolvedController>& resolved)
      : plant(resolved->robot, plantOptions(*resolved)) {
    if (resolved->cartesian()) {
      wrapper = std::make_unique<pipeline::CartesianWrapper>(resolved);
    } else {
      wrapper = std::make_unique<pipeline::JointWrapper>(resolved);
    }
    state = JointState::zero(plant.dof());
    torque.setZero(plant.dof());
    plant.read(state);
    std::visit([&](auto& w) { w->activate(state); }, wrapper);
  }

  static sim::PlantOptions plantOptions(const pipeline::ResolvedController& resolved) {
    sim::PlantOptions options;
    options.tip_frame = resolved.config.tip_frame;
    return options;
  }

  void cycle() {
    plant.read(state);
    const std::span<double> out(torque.data(), static_cast<std::size_t>(torque.size()));
    wrote =
        std::visit([&](auto& w) { return w->cycle(state, plant.controlPeriod(), out); }, wrapper);
    if (wrote) {
      plant.write(out);
    }
    plant.step();
  }

  py::dict observation() {
    plant.read(state);
    py::dict obs;
    obs["time"] = plant.simTime();
    obs["position"] = array(state.position);
    obs["velocity"] = array(state.velocity);
    obs["effort"] = array(state.effort);
    obs["torque_command"] = array(torque);
    const Eigen::Isometry3d tcp = plant.tcpPose();
    const Eigen::Vector3d p = tcp.translation();
    const Eigen::Quaterniond q(tcp.linear());
    obs["tcp_position"] = array(p);
    obs["tcp_orientation"] = array(q.coeffs());  // Eigen stores x y z w
    obs["contact_wrench"] = array(plant.toolContactWrench());
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
  if (!command.is_none()) {
    const py::dict kwargs = command.cast<py::dict>();
    const double stamp_s = session_->plant.simTime();
    const pipeline::Verdict verdict = std::visit(
        [&](auto& w) {
          using Wrapper = std::remove_reference_t<decltype(*w)>;
          if constexpr (std::is_same_v<Wrapper, pipeline::CartesianWrapper>) {
            CartesianCommand c = cartesianFromKwargs(kwargs, dof(), w->lastAccepted());
            c.stamp_s = stamp_s;
            return w->submit(c);
          } else {
            JointCommand c = jointFromKwargs(kwargs, dof(), w->lastAccepted());
            c.stamp_s = stamp_s;
            return w->submit(c);
          }
        },
        session_->wrapper);
    info["accepted"] = verdict.accepted;
    info["reason"] = verdict.accepted ? "" : std::string(pipeline::toString(verdict.reason));
    info["message"] = verdict.message;
  }
  {
    const py::gil_scoped_release release;
    for (int i = 0; i < steps_per_action_; ++i) {
      session_->cycle();
    }
  }
  const pipeline::DiagnosticsSnapshot d =
      std::visit([](auto& w) { return w->diagnostics(); }, session_->wrapper);
  const bool terminated = d.state == pipeline::WrapperState::kFault;
  const bool truncated = max_time_s_ > 0.0 && session_->plant.simTime() >= max_time_s_;
  info["state"] = std::string(pipeline::toString(d.state));
  info["last_fault"] = d.last_fault;
  return py::make_tuple(session_->observation(), 0.0, terminated, truncated, info);
}

}  // namespace comply::python
