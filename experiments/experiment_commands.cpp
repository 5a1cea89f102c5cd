#include "experiment_commands.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <utility>

#include "chunks/chunk_experiment.hpp"
#include "comply/core/output_folder.hpp"
#include "connector_mating/connector_mating_experiment.hpp"
#include "cross_platform/cross_platform_experiment.hpp"
#include "output_modes/output_modes_experiment.hpp"
#include "passivity/passivity_experiment.hpp"
#include "surface_following/surface_following_experiment.hpp"

namespace comply::experiments {

struct Commands::State {
  CrossPlatformOptions cross_platform;
  SurfaceFollowingOptions surface;
  ConnectorMatingOptions mating;
  PassivityOptions passivity;
  ChunkOptions chunks;
  OutputModesOptions output_modes;
  CLI::App* cross_platform_command = nullptr;
  CLI::App* surface_command = nullptr;
  CLI::App* mating_command = nullptr;
  CLI::App* passivity_command = nullptr;
  CLI::App* chunks_command = nullptr;
  CLI::App* output_modes_command = nullptr;
};

namespace {

/// Where the default output folders are: out/<experiment> in the working folder.
const std::filesystem::path kDefaultOutRoot = "out";

void addOutOption(CLI::App& command, std::filesystem::path& out_dir) {
  command.add_option("--out", out_dir, "output folder, made if missing (its parent must exist)")
      ->capture_default_str();
}

/// The parsed experiment without --out writes to its default, out/<experiment>: out/ is made
/// for it. A folder given with --out is made only as its last folder, by the experiment.
void makeDefaultOutRoot(std::initializer_list<const CLI::App*> commands) {
  for (const CLI::App* command : commands) {
    if (command->parsed() && command->count("--out") == 0) {
      makeOutputFolder(kDefaultOutRoot);
    }
  }
}

CLI::App* addCrossPlatform(CLI::App& experiment, CrossPlatformOptions& options) {
  CLI::App* command = experiment.add_subcommand("cross-platform",
                                                "one plugin, one command, four robots, one target");
  addOutOption(*command, options.out_dir);
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
  addOutOption(*command, options.out_dir);
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
  addOutOption(*command, options.out_dir);
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

CLI::App* addPassivity(CLI::App& experiment, PassivityOptions& options) {
  CLI::App* command = experiment.add_subcommand(
      "passivity", "adversarially streamed gains: no gain stage vs ramps vs energy tank");
  addOutOption(*command, options.out_dir);
  command
      ->add_option("--duration", options.duration_s,
                   "simulated seconds of each adversarial scenario (the normal task takes 3 s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--conditions", options.conditions,
                   "none (no gain stage), ramps (gain_ramps), tank (gain_ramps and passivity), "
                   "tank_only (passivity without gain_ramps)")
      ->capture_default_str()
      ->check(CLI::IsMember(namesIn(passivity::kConditions)));
  command
      ->add_option("--torque-rate-limit", options.torque_rate_limit_nm_per_s,
                   "ablation: the torque-rate limit per joint [N m/s] (default: the controller "
                   "file's)")
      ->check(CLI::PositiveNumber);
  return command;
}

CLI::App* addOutputModes(CLI::App& experiment, OutputModesOptions& options) {
  CLI::App* command = experiment.add_subcommand(
      "output-modes", "one law on torque, position and velocity drives: stiffness, contact, tool");
  addOutOption(*command, options.out_dir);
  return command;
}

CLI::App* addChunks(CLI::App& experiment, ChunkOptions& options) {
  CLI::App* command = experiment.add_subcommand(
      "chunks", "a circle from a policy's actions: stepped setpoints vs timed chunks");
  addOutOption(*command, options.out_dir);
  command->add_option("--duration", options.settings.duration_s, "simulated seconds per run")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 600.0));
  command
      ->add_option("--conditions", options.conditions,
                   "stepped_<rate>hz (one target per step, held) or chunks_<rate>hz (16 waypoints "
                   "1/15 s apart), e.g. chunks_10hz")
      ->capture_default_str();
  command
      ->add_option("--latency", options.settings.latency_s,
                   "s from the observation to the action at the host")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.5));
  command
      ->add_option("--action-error", options.settings.action_error_m,
                   "m, standard deviation of each action's error per axis")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.02));
  command->add_option("--seed", options.settings.seed, "of the actions' errors")
      ->capture_default_str();
  return command;
}

}  // namespace

Commands::Commands(std::unique_ptr<State> state) : state_(std::move(state)) {}
Commands::Commands(Commands&&) noexcept = default;
Commands& Commands::operator=(Commands&&) noexcept = default;
Commands::~Commands() = default;

bool Commands::parsed() const {
  return state_->cross_platform_command->parsed() || state_->surface_command->parsed() ||
         state_->mating_command->parsed() || state_->passivity_command->parsed() ||
         state_->chunks_command->parsed() || state_->output_modes_command->parsed();
}

int Commands::run(std::ostream& out, std::ostream& err) const {
  makeDefaultOutRoot({state_->cross_platform_command, state_->surface_command,
                      state_->mating_command, state_->passivity_command, state_->chunks_command,
                      state_->output_modes_command});
  if (state_->mating_command->parsed()) {
    return connectorMatingCommand(state_->mating, out, err);
  }
  if (state_->passivity_command->parsed()) {
    return passivityCommand(state_->passivity, out, err);
  }
  if (state_->chunks_command->parsed()) {
    return chunksCommand(state_->chunks, out, err);
  }
  if (state_->output_modes_command->parsed()) {
    return outputModesCommand(state_->output_modes, out, err);
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
  state->passivity_command = addPassivity(*experiment, state->passivity);
  state->chunks_command = addChunks(*experiment, state->chunks);
  state->output_modes_command = addOutputModes(*experiment, state->output_modes);
  return Commands(std::move(state));
}

}  // namespace comply::experiments
