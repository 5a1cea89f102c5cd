#include "experiment_commands.hpp"

#include <CLI/CLI.hpp>
#include <memory>
#include <utility>

#include "connector_mating/connector_mating_experiment.hpp"
#include "cross_platform/cross_platform_experiment.hpp"
#include "surface_following/surface_following_experiment.hpp"

namespace comply::experiments {

struct Commands::State {
  CrossPlatformOptions cross_platform;
  SurfaceFollowingOptions surface;
  ConnectorMatingOptions mating;
  CLI::App* cross_platform_command = nullptr;
  CLI::App* surface_command = nullptr;
  CLI::App* mating_command = nullptr;
};

namespace {

CLI::App* addCrossPlatform(CLI::App& experiment, CrossPlatformOptions& options) {
  CLI::App* command = experiment.add_subcommand("cross-platform",
                                                "one plugin, one command, four robots, one target");
  command->add_option("--out", options.out_dir, "output folder")->capture_default_str();
  command
      ->add_option("--duration", options.duration_s,
                   "simulated seconds per robot (default: the task's)")
      ->check(CLI::PositiveNumber);
  command->add_option("--robots", options.robots, "robots to run")->capture_default_str();
  return command;
}

CLI::App* addSurfaceFollowing(CLI::App& experiment, SurfaceFollowingOptions& options) {
  CLI::App* command = experiment.add_subcommand(
      "surface-following", "probe along a curved fixture: fixed-frame vs task-aligned gains");
  command->add_option("--out", options.out_dir, "output folder")->capture_default_str();
  command->add_option("--speed", options.speed_m_per_s, "traverse speed [m/s]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--path-fraction", options.path_fraction, "traverse only this share of the path")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1.0));
  return command;
}

CLI::App* addConnectorMating(CLI::App& experiment, ConnectorMatingOptions& options) {
  CLI::App* command = experiment.add_subcommand(
      "connector-mating", "peg into a tilted socket: TCP-fixed vs task-aligned compliance");
  command->add_option("--out", options.out_dir, "output folder")->capture_default_str();
  command->add_option("--offsets", options.offsets_deg, "angular offsets [deg]")
      ->capture_default_str();
  command
      ->add_option("--force-limit", options.axial_force_limit_n,
                   "axial force that ends a trial before seating [N]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--conditions", options.conditions,
                   "where the insertion gains are expressed: tcp_fixed (commanded TCP), "
                   "tcp_measured (measured TCP), task_aligned (socket), online_fsf (Frenet-Serret "
                   "frame of the measured TCP path, the reference advancing along it; orientation "
                   "held), online_fsf_oriented (the same, the peg turned onto the frame)")
      ->capture_default_str()
      ->check(CLI::IsMember(
          {"tcp_fixed", "tcp_measured", "task_aligned", "online_fsf", "online_fsf_oriented"}));
  command
      ->add_option("--rotational-stiffness", options.rotational_stiffness_nm_per_rad,
                   "rotational stiffness during insertion [N m/rad]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--plant-friction-scale", options.plant_friction_scale,
                   "ablation: multiplies the simulated arm's joint Coulomb friction")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--nullspace-stiffness", options.nullspace_stiffness_nm_per_rad,
                   "ablation: posture spring during insertion, towards the joints at its start "
                   "[N m/rad] (default: the controller's)")
      ->check(CLI::NonNegativeNumber);
  return command;
}

}  // namespace

Commands::Commands(std::unique_ptr<State> state) : state_(std::move(state)) {}
Commands::Commands(Commands&&) noexcept = default;
Commands& Commands::operator=(Commands&&) noexcept = default;
Commands::~Commands() = default;

bool Commands::parsed() const {
  return state_->cross_platform_command->parsed() || state_->surface_command->parsed() ||
         state_->mating_command->parsed();
}

int Commands::run(std::ostream& out, std::ostream& err) const {
  if (state_->mating_command->parsed()) {
    return connectorMatingCommand(state_->mating, out, err);
  }
  if (state_->surface_command->parsed()) {
    return surfaceFollowingCommand(state_->surface, out, err);
  }
  return crossPlatformCommand(state_->cross_platform, out, err);
}

Commands addCommands(CLI::App& app) {
  auto state = std::make_unique<Commands::State>();
  CLI::App* experiment =
      app.add_subcommand("experiment", "reproduce an experiment of the evaluation");
  experiment->require_subcommand(1);
  state->cross_platform_command = addCrossPlatform(*experiment, state->cross_platform);
  state->surface_command = addSurfaceFollowing(*experiment, state->surface);
  state->mating_command = addConnectorMating(*experiment, state->mating);
  return Commands(std::move(state));
}

}  // namespace comply::experiments
