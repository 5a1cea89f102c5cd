#include "passivity/passivity_run.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "passivity/energy_meter.hpp"
#include "passivity/gain_streams.hpp"
#include "passivity/wall.hpp"
#include "source_dir.hpp"

namespace comply::experiments::passivity {
namespace {

// Contact with the wall: touching once the ball reaches the face, lost once it is this far away
// again (MuJoCo's contact chatters by micrometres at the step rate; a rebound is millimetres).
constexpr double kLostGapM = 0.001;
// A force sensor's view of the contact force: a 20 ms moving average, as the other contact
// experiments read it (host::averagedContactForce()).
constexpr std::size_t kForceWindowCycles = 20;

/// The command stream of a scenario and the gains the controller starts with.
struct Stream {
  std::unique_ptr<task::CartesianSource> source;
  CartesianCommand initial;
};

Stream streamOf(Scenario scenario, const host::TcpPose& home, const Wall& wall,
                const CartesianCommand& controller) {
  // The free-space target: 5 cm along base x, the orientation held.
  const Eigen::Vector3d free_target = home.position + 0.05 * Eigen::Vector3d::UnitX();
  Stream stream;
  if (scenario == Scenario::kNormalTask) {
    auto smooth = std::make_unique<SmoothTaskStream>(home.position, home.orientation, controller);
    stream.initial = smooth->gains(0.0);
    stream.source = std::move(smooth);
    return stream;
  }
  const PumpedGain pumped =
      scenario == Scenario::kFreeSpaceFrame ? PumpedGain::kTaskFrame : PumpedGain::kStiffness;
  const Eigen::Vector3d target =
      scenario == Scenario::kWallContact ? wall.pressingReference() : free_target;
  auto pump = std::make_unique<PumpStream>(pumped, target, home.orientation, controller);
  stream.initial = pump->gains(false);
  stream.source = std::move(pump);
  return stream;
}

pipeline::WrapperConfig configOf(Condition condition, const RunSettings& settings) {
  pipeline::WrapperConfig config = host::simControllerConfig(
      "fr3", "", sourcePath("config/sim/cartesian_impedance.yaml").string());
  config.gain_ramps.enabled = condition == Condition::kRamps || condition == Condition::kTank;
  config.passivity.enabled = condition == Condition::kTank || condition == Condition::kTankOnly;
  // The experiment measures what the schedules do to the energy, the gain stage's subject; the
  // stability guard would end the runs without it in FAULT once a joint overspeeds, and the motion
  // governor would bound the speeds whatever the gains (with it, free_space_stiffness under `none`
  // peaks at 21 J instead of 174 J in the 1 s run: docs/safety.md covers that layer).
  config.stability_guard.enabled = false;
  config.governor.enabled = false;
  if (settings.torque_rate_limit_nm_per_s) {
    std::fill(config.torque_rate_limit.begin(), config.torque_rate_limit.end(),
              *settings.torque_rate_limit_nm_per_s);
  }
  return config;
}

/// The stiffness a bus gives along base x: x^T R K R^T x.
double stiffnessAlongX(const comply_cartesian_command& law) {
  const Eigen::Quaterniond frame(law.task_frame[3], law.task_frame[0], law.task_frame[1],
                                 law.task_frame[2]);
  const Eigen::Vector3d x_in_task = frame.normalized().conjugate() * Eigen::Vector3d::UnitX();
  return x_in_task.dot(
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(law.stiffness_translational) *
      x_in_task);
}

/// The springs' gains (both stiffness blocks, the task frame, the nullspace stiffness).
void copyStiffness(const comply_cartesian_command& from, comply_cartesian_command& to) {
  std::copy_n(from.stiffness_translational, 9, to.stiffness_translational);
  std::copy_n(from.stiffness_rotational, 9, to.stiffness_rotational);
  std::copy_n(from.task_frame, 4, to.task_frame);
  std::copy_n(from.nullspace_stiffness, COMPLY_MAX_DOF, to.nullspace_stiffness);
}

/// The experiment's side of each cycle: before it, the stream's command is submitted; after it,
/// the arm's energy and the rest are measured and written to the trace.
class Recorder final : public hardware::LoopObserver {
 public:
  Recorder(Scenario scenario, pipeline::Wrapper<CartesianCommand>& wrapper,
           task::CartesianSource& source, sim::SimulatedRobot& plant, const Wall& wall,
           std::ostream& trace)
      : scenario_(scenario),
        wrapper_(wrapper),
        source_(source),
        plant_(plant),
        wall_(wall),
        trace_(trace),
        meter_(wrapper.controller(), plant) {
    trace_ << "time_s,kinetic_j,spring_j,energy_j,tank_j,stiffness_x_n_per_m,error_mm,contact_n,"
              "gap_mm,refused_j\n";
  }

  void beforeCycle(std::uint64_t /*index*/, double t) override {
    if (std::optional<CartesianCommand> command = source_.next(t, wrapper_.measuredPose())) {
      const pipeline::Verdict verdict = wrapper_.submit(*command);
      if (!verdict.accepted) {
        if (has(command->fields, CommandField::kPosition)) {
          throw std::runtime_error("passivity " + nameOf(scenario_) +
                                   ": the reference was refused: " + verdict.message);
        }
        ++result_.rejections;
      }
    }
  }

  void afterCycle(const hardware::CycleRecord& record) override {
    const auto& law = std::get<comply_cartesian_command>(wrapper_.controller().lawBus());
    meter_.measure(record.state->position);
    const double spring_j = meter_.springEnergy(law);
    if (record.index > 0) {
      // The previous cycle's gains on this cycle's reference: a moving reference is not a gain's
      // doing.
      comply_cartesian_command previous = law;
      copyStiffness(previous_law_, previous);
      result_.gain_work_j += spring_j - meter_.springEnergy(previous);
    }
    previous_law_ = law;
    const double kinetic_j = meter_.kineticEnergy();
    const double energy_j = kinetic_j + spring_j;
    if (record.index == 0) {
      result_.initial_energy_j = energy_j;
    }
    result_.peak_energy_j = std::max(result_.peak_energy_j, energy_j);
    result_.final_energy_j = energy_j;

    const pipeline::PassivitySnapshot tank = wrapper_.controller().diagnostics().passivity();
    refusing_cycles_ += tank.refused_j > 0.0 ? 1 : 0;
    ++cycles_;
    const Eigen::Isometry3d tcp = plant_.tcpPose();
    const double error_m =
        (tcp.translation() - Eigen::Vector3d(law.position[0], law.position[1], law.position[2]))
            .norm();
    squared_error_sum_ += error_m * error_m;
    max_error_m_ = std::max(max_error_m_, error_m);
    const double contact_n = plant_.toolContactWrench().head<3>().norm();
    const bool wall = scenario_ == Scenario::kWallContact;
    const double gap_m = wall ? wall_.gap(tcp) : std::nan("");
    if (wall) {
      followContact(contact_n, gap_m);
    }

    trace_ << record.time_s << ',' << kinetic_j << ',' << spring_j << ',' << energy_j << ','
           << tank.tank_energy_j << ',' << stiffnessAlongX(law) << ',' << 1e3 * error_m << ','
           << contact_n << ',' << 1e3 * gap_m << ',' << tank.refused_j << '\n';
  }

  /// The result once the loop has run.
  RunResult finish(bool tank_on) {
    const auto& law = std::get<comply_cartesian_command>(wrapper_.controller().lawBus());
    result_.stiffness_final_n_per_m = stiffnessAlongX(law);
    const pipeline::DiagnosticsSnapshot diagnostics = wrapper_.diagnostics();
    result_.faults = diagnostics.faults;
    result_.rate_limit_hits = diagnostics.rate_limit_hits;
    result_.effort_limit_hits = diagnostics.effort_limit_hits;
    if (tank_on) {
      result_.tank_final_j = diagnostics.passivity.tank_energy_j;
      result_.tank_injected_j = diagnostics.passivity.injected_j;
      result_.tank_dissipated_j = diagnostics.passivity.dissipated_j;
      result_.refusing_share = static_cast<double>(refusing_cycles_) /
                               static_cast<double>(std::max<std::uint64_t>(cycles_, 1));
    }
    if (scenario_ == Scenario::kWallContact) {
      result_.peak_contact_force_n = peak_contact_n_;
      result_.peak_contact_force_mean_n = peak_mean_contact_n_;
      result_.contact_losses = contact_losses_;
      result_.rebound_mm = 1e3 * rebound_m_;
    }
    if (scenario_ == Scenario::kNormalTask) {
      result_.tracking_rms_mm =
          1e3 *
          std::sqrt(squared_error_sum_ / static_cast<double>(std::max<std::uint64_t>(cycles_, 1)));
      result_.tracking_max_mm = 1e3 * max_error_m_;
    }
    return result_;
  }

 private:
  void followContact(double contact_n, double gap_m) {
    peak_contact_n_ = std::max(peak_contact_n_, contact_n);
    window_.push_back(contact_n);
    window_sum_n_ += contact_n;
    if (window_.size() > kForceWindowCycles) {
      window_sum_n_ -= window_.front();
      window_.pop_front();
    }
    peak_mean_contact_n_ =
        std::max(peak_mean_contact_n_, window_sum_n_ / static_cast<double>(window_.size()));
    if (gap_m <= 0.0) {
      touched_ = in_contact_ = true;
    } else if (in_contact_ && gap_m > kLostGapM) {
      in_contact_ = false;
      ++contact_losses_;
    }
    if (touched_) {
      rebound_m_ = std::max(rebound_m_, gap_m);
    }
  }

  Scenario scenario_;
  pipeline::Wrapper<CartesianCommand>& wrapper_;
  task::CartesianSource& source_;
  sim::SimulatedRobot& plant_;
  const Wall& wall_;
  std::ostream& trace_;
  EnergyMeter meter_;
  comply_cartesian_command previous_law_{};
  RunResult result_;
  std::uint64_t cycles_ = 0;
  std::uint64_t refusing_cycles_ = 0;
  double squared_error_sum_ = 0.0;
  double max_error_m_ = 0.0;
  double peak_contact_n_ = 0.0;
  double peak_mean_contact_n_ = 0.0;
  std::deque<double> window_;
  double window_sum_n_ = 0.0;
  bool touched_ = false;
  bool in_contact_ = false;
  std::int64_t contact_losses_ = 0;
  double rebound_m_ = 0.0;
};

}  // namespace

std::string nameOf(Scenario scenario) {
  return std::string(nameIn(kScenarios, scenario, "?"));
}

std::string nameOf(Condition condition) {
  return std::string(nameIn(kConditions, condition, "?"));
}

Condition conditionOf(const std::string& name) {
  if (const auto condition = valueIn(kConditions, name)) {
    return *condition;
  }
  std::string known;
  for (const std::string& condition : namesIn(kConditions)) {
    known += (known.empty() ? "" : ", ") + condition;
  }
  throw std::invalid_argument("unknown passivity condition '" + name + "' (" + known + ")");
}

RunResult runScenario(Scenario scenario, Condition condition, const RunSettings& settings,
                      const std::filesystem::path& trace_file) {
  const host::TcpPose home = host::homeTcpPose("fr3");
  Eigen::Isometry3d home_tcp = Eigen::Isometry3d::Identity();
  home_tcp.translation() = home.position;
  home_tcp.linear() = home.orientation.toRotationMatrix();
  const Wall wall(home_tcp);

  pipeline::WrapperConfig config = configOf(condition, settings);
  Stream stream = streamOf(scenario, home, wall, config.initial_cartesian);
  // The run starts with the stream's first gains in force, so that every condition starts from
  // the same state and the first command changes only the reference.
  copyGains(stream.initial, config.initial_cartesian);
  const std::shared_ptr<const pipeline::ResolvedController> resolved =
      pipeline::resolveController(config);

  sim::PlantOptions plant_options;
  plant_options.tip_frame = resolved->config.tip_frame;
  // Physics steps per control period: 2 in free space, as the surface-following runs; 4 for the
  // wall's rigid contact (solref 5 ms), as connector mating's.
  plant_options.substeps = scenario == Scenario::kWallContact ? 4 : 2;
  if (scenario == Scenario::kWallContact) {
    const std::filesystem::path wall_file = trace_file.parent_path() / "wall.xml";
    std::ofstream(wall_file) << wall.fragment();
    plant_options.scene.tool = sourcePath("examples/sim/probe_tool.xml");
    plant_options.scene.objects.push_back(wall_file);
  }
  sim::SimulatedRobot plant(resolved->robot, plant_options);
  pipeline::Wrapper<CartesianCommand> wrapper(resolved);
  JointState state = JointState::zero(wrapper.dof());
  plant.read(state);
  wrapper.activate(state);

  const double period_s = plant.controlPeriod();
  const double run_s = scenario == Scenario::kNormalTask
                           ? SmoothTaskStream::kMotionS + SmoothTaskStream::kHoldS
                           : settings.duration_s;
  task::PacedSource<CartesianCommand> paced(*stream.source, kPolicyPeriodS, period_s);
  std::ofstream trace(trace_file);
  Recorder recorder(scenario, wrapper, paced, plant, wall, trace);
  sim::SimulatedClock clock(plant);
  hardware::ControlLoop loop(
      plant, wrapper, clock,
      {.period_s = period_s, .cycles = static_cast<std::uint64_t>(std::llround(run_s / period_s))});
  loop.setObserver(&recorder);
  loop.run();
  return recorder.finish(config.passivity.enabled);
}

}  // namespace comply::experiments::passivity
