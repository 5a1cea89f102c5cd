#include "chunks/chunk_run.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "source_dir.hpp"

namespace comply::experiments::chunks {
namespace {

// The circle's speed ramps up over this time, so that the task itself starts without a jump.
constexpr double kRampS = 0.5;

/// The circle in the y-z plane through the home pose, started with a smooth speed ramp.
class Circle {
 public:
  Circle(const Eigen::Vector3d& home, const RunSettings& settings)
      : home_(home),
        radius_m_(settings.circle_radius_m),
        rate_rad_per_s_(2.0 * std::numbers::pi / settings.circle_period_s),
        start_s_(settings.start_s) {}

  [[nodiscard]] Eigen::Vector3d at(double t_s) const {
    const double phase = phaseAt(t_s);
    return home_ + radius_m_ * Eigen::Vector3d(0.0, std::sin(phase), 1.0 - std::cos(phase));
  }

 private:
  /// The angle travelled: the rate times the time, its first kRampS on a smoothstep ramp.
  [[nodiscard]] double phaseAt(double t_s) const {
    const double since = t_s - start_s_;
    if (since <= 0.0) {
      return 0.0;
    }
    if (since < kRampS) {
      const double u = since / kRampS;
      return rate_rad_per_s_ * kRampS * (u * u * u - 0.5 * u * u * u * u);
    }
    return rate_rad_per_s_ * (0.5 * kRampS + since - kRampS);
  }

  Eigen::Vector3d home_;
  double radius_m_;
  double rate_rad_per_s_;
  double start_s_;
};

/// The policy's side before each cycle (its actions, as they reach the host) and the metrics
/// after it.
class Policy final : public hardware::LoopObserver {
 public:
  Policy(const Condition& condition, const RunSettings& settings, const Circle& circle,
         const Eigen::Quaterniond& orientation, pipeline::Wrapper<CartesianCommand>& wrapper,
         sim::SimulatedRobot& plant, double period_s, std::ostream& trace)
      : condition_(condition),
        settings_(settings),
        circle_(circle),
        orientation_(orientation),
        wrapper_(wrapper),
        plant_(plant),
        period_s_(period_s),
        trace_(trace),
        random_(settings.seed),
        next_observation_s_(settings.start_s) {
    trace_ << "time_s,target_y,target_z,reference_y,reference_z,tcp_y,tcp_z,reference_speed,"
              "torque_rate\n";
  }

  void beforeCycle(std::uint64_t /*index*/, double t_s) override {
    // The action computed on the observation at next_observation_s_ arrives latency_s later.
    while (t_s >= next_observation_s_ + settings_.latency_s - 1e-9) {
      act(next_observation_s_, t_s);
      next_observation_s_ += 1.0 / condition_.rate_hz;
    }
  }

  void afterCycle(const hardware::CycleRecord& record) override {
    const auto& law = std::get<comply_cartesian_command>(wrapper_.controller().lawBus());
    const Eigen::Vector3d reference(law.position[0], law.position[1], law.position[2]);
    const Eigen::Vector3d tcp = plant_.tcpPose().translation();
    const Eigen::Vector3d target = circle_.at(record.time_s);
    double torque_rate = 0.0;
    if (!last_torque_.empty()) {
      for (std::size_t j = 0; j < record.torque.size(); ++j) {
        torque_rate =
            std::max(torque_rate, std::abs(record.torque[j] - last_torque_[j]) / period_s_);
      }
    }
    last_torque_.assign(record.torque.begin(), record.torque.end());
    differences(reference);
    if (record.time_s >= settings_.settle_s) {
      const double error_m = (tcp - target).norm();
      squared_error_sum_ += error_m * error_m;
      ++settled_cycles_;
      result_.max_error_mm = std::max(result_.max_error_mm, 1e3 * error_m);
    }
    result_.max_torque_rate_nm_per_s = std::max(result_.max_torque_rate_nm_per_s, torque_rate);
    trace_ << record.time_s << ',' << target.y() << ',' << target.z() << ',' << reference.y() << ','
           << reference.z() << ',' << tcp.y() << ',' << tcp.z() << ','
           << (history_ >= 2 ? (reference - references_[1]).norm() / period_s_ : 0.0) << ','
           << torque_rate << '\n';
  }

  RunResult finish() {
    const pipeline::DiagnosticsSnapshot diagnostics = wrapper_.diagnostics();
    result_.rate_limit_hits = diagnostics.rate_limit_hits;
    result_.faults = diagnostics.faults;
    result_.rmse_mm =
        1e3 * std::sqrt(squared_error_sum_ /
                        static_cast<double>(std::max<std::uint64_t>(settled_cycles_, 1)));
    return result_;
  }

 private:
  Eigen::Vector3d actionError() {
    std::normal_distribution<double> error(0.0, settings_.action_error_m);
    return {error(random_), error(random_), error(random_)};
  }

  /// The action on the observation at `observed_s`, submitted at `now_s` (the host's clock).
  void act(double observed_s, double now_s) {
    ++result_.actions;
    pipeline::Verdict verdict;
    if (condition_.mode == Mode::kStepped) {
      CartesianCommand command = CartesianCommand::zero(wrapper_.dof());
      command.stamp_s = now_s;
      command.fields = CommandField::kPosition;
      command.position = circle_.at(observed_s + settings_.step_s) + actionError();
      command.orientation = orientation_;
      verdict = wrapper_.submit(command);
    } else {
      CartesianChunk chunk;
      chunk.stamp_s = now_s;
      chunk.fields = CommandField::kPosition;
      const Eigen::Vector3d error = actionError();  // one per chunk: the policy's view of it
      for (int j = 0; j < settings_.chunk_steps; ++j) {
        const double t = observed_s + j * settings_.step_s;
        ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(wrapper_.dof())};
        waypoint.command.position = circle_.at(t) + error;
        waypoint.command.orientation = orientation_;
        chunk.waypoints.push_back(waypoint);
      }
      verdict = wrapper_.submitChunk(chunk, now_s);
    }
    if (!verdict.accepted) {
      throw std::runtime_error("chunks " + condition_.name +
                               ": an action was refused: " + verdict.message);
    }
  }

  /// Finite differences of the reference: velocity step, acceleration and jerk.
  void differences(const Eigen::Vector3d& reference) {
    for (int i = 3; i > 0; --i) {
      references_[i] = references_[i - 1];
    }
    references_[0] = reference;
    history_ = std::min(history_ + 1, 4);
    const double dt = period_s_;
    if (history_ >= 3) {
      const Eigen::Vector3d second = references_[0] - 2 * references_[1] + references_[2];
      result_.max_reference_velocity_step =
          std::max(result_.max_reference_velocity_step, second.norm() / dt);
      result_.max_reference_acceleration =
          std::max(result_.max_reference_acceleration, second.norm() / (dt * dt));
    }
    if (history_ >= 4) {
      const Eigen::Vector3d third =
          references_[0] - 3 * references_[1] + 3 * references_[2] - references_[3];
      result_.max_reference_jerk =
          std::max(result_.max_reference_jerk, third.norm() / (dt * dt * dt));
    }
  }

  const Condition& condition_;
  const RunSettings& settings_;
  const Circle& circle_;
  Eigen::Quaterniond orientation_;
  pipeline::Wrapper<CartesianCommand>& wrapper_;
  sim::SimulatedRobot& plant_;
  double period_s_;
  std::ostream& trace_;
  std::mt19937 random_;
  double next_observation_s_;
  RunResult result_;
  std::vector<double> last_torque_;
  Eigen::Vector3d references_[4];
  int history_ = 0;
  double squared_error_sum_ = 0.0;
  std::uint64_t settled_cycles_ = 0;
};

}  // namespace

RunResult runCondition(const Condition& condition, const RunSettings& settings,
                       const std::filesystem::path& trace_file) {
  if (!(condition.rate_hz > 0.0) || settings.chunk_steps < 2 ||
      settings.chunk_steps > kMaxChunkWaypoints) {
    throw std::invalid_argument("chunks: the policy rate must be > 0 and a chunk 2 to " +
                                std::to_string(kMaxChunkWaypoints) + " steps");
  }
  const pipeline::WrapperConfig config = host::simControllerConfig(
      "fr3", "", sourcePath("config/sim/cartesian_impedance.yaml").string());
  const std::shared_ptr<const pipeline::ResolvedController> resolved =
      pipeline::resolveController(config);
  sim::PlantOptions plant_options;
  plant_options.tip_frame = resolved->config.tip_frame;
  sim::SimulatedRobot plant(resolved->robot, plant_options);
  pipeline::Wrapper<CartesianCommand> wrapper(resolved);
  JointState state = JointState::zero(wrapper.dof());
  plant.read(state);
  wrapper.activate(state);

  const host::TcpPose home = host::homeTcpPose("fr3");
  const Circle circle(home.position, settings);
  const double period_s = plant.controlPeriod();
  std::ofstream trace(trace_file);
  Policy policy(condition, settings, circle, home.orientation, wrapper, plant, period_s, trace);
  sim::SimulatedClock clock(plant);
  hardware::ControlLoop loop(
      plant, wrapper, clock,
      {.period_s = period_s,
       .cycles = static_cast<std::uint64_t>(std::llround(settings.duration_s / period_s))});
  loop.setObserver(&policy);
  loop.run();
  return policy.finish();
}

}  // namespace comply::experiments::chunks
