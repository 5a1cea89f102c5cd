// The set-up of a benchmarked wrapper (see bench_variant.hpp).

#include "bench_variant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "comply/host/controller_setup.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::host::bench {
namespace {

/// A chunk that lasts the whole run: 64 waypoints around the measured TCP, the stiffness and the
/// task frame changing at each, so every cycle evaluates the curve, the gains and the frame.
CartesianChunk benchChunk(const MeasuredPose& measured, double run_s, int dof) {
  CartesianChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kTaskFrame;
  // The waypoints zigzag within what the intake accepts of an arm however short the run: the
  // amplitude shrinks with the square of their spacing, so speeds and accelerations stay low.
  const double spacing_s = run_s / (kMaxChunkWaypoints - 1);
  const double amplitude_m = std::min(0.01, 1.0 * spacing_s * spacing_s);
  for (int k = 0; k < kMaxChunkWaypoints; ++k) {
    const double t = spacing_s * k;
    ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(dof)};
    waypoint.command.position =
        measured.tcp_position + amplitude_m * Eigen::Vector3d(std::sin(k), std::cos(k), 0.0);
    waypoint.command.orientation = measured.tcp_orientation;
    waypoint.command.stiffness_translational = (500.0 + 20.0 * k) * Eigen::Matrix3d::Identity();
    waypoint.command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
    waypoint.command.task_frame =
        Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitZ()) * Eigen::Quaterniond::Identity();
    chunk.waypoints.push_back(waypoint);
  }
  return chunk;
}

/// Force along a turned task frame's z; its x and y under the contact-force limit.
void submitForceCommand(pipeline::Wrapper<CartesianCommand>& wrapper,
                        const std::string& wrapper_name) {
  CartesianCommand command = CartesianCommand::zero(wrapper.dof());
  command.fields = CommandField::kForce | CommandField::kTaskFrame;
  command.task_frame =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::Quaterniond::Identity();
  command.force_axes[2] = 1.0;
  command.wrench_target[2] = 5.0;
  const pipeline::Verdict verdict = wrapper.submit(command);
  if (!verdict.accepted) {
    throw std::runtime_error(wrapper_name +
                             ": the benchmark's force command was refused: " + verdict.message);
  }
}

}  // namespace

pipeline::WrapperConfig variantConfig(const std::string& robot, const std::string& plugin,
                                      const Variant& variant) {
  pipeline::WrapperConfig config = host::controllerConfig(robot, plugin);
  config.initial_cartesian.damping_mode = variant.damping_mode;
  config.observer.enabled = variant.observer || variant.force || variant.reflex;
  if (variant.reflex) {
    // Armed, its thresholds out of the replayed motion's reach: the cost is the check of every
    // cycle (the observer's wrench solved for it, the ellipsoid in the task frame), not a hold.
    config.reflex.enabled = true;
    config.reflex.force_n = config.reflex.max_force_n = 1e4;
    config.reflex.torque_nm = config.reflex.max_torque_nm = 1e3;
  }
  if (variant.force) {
    config.force_control.contact_force_limit_n = Eigen::Vector3d(30.0, 30.0, 0.0);
  }
  config.output.mode = variant.output;
  if (variant.walls) {
    // Around every robot's reach, so the law's cycle is the plain one: the cost is the stage's
    // (a reference checked against ten planes, the barrier's distances), not a different motion.
    config.walls.planes = {{{1.2, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                           {{0.0, 0.9, 0.0}, {0.0, 1.0, 0.0}},
                           {{0.0, -0.9, 0.0}, {0.0, -1.0, 0.0}},
                           {{0.0, 0.0, 1.4}, {0.0, 0.0, 1.0}}};
    config.walls.boxes = {{{-1.5, -1.5, -0.5}, {1.5, 1.5, 1.5}}};
  }
  // The defaults (hands, quasi-static): the stage computes the mass along the replayed TCP's
  // motion every cycle; its few multiplications more when it scales or brakes are not the cost.
  config.contact_speed.enabled = variant.contact_speed;
  if (variant.gain_stage) {
    // Ramps and tank on, the tank far from full so that it refills (and, with ratios, bounds the
    // damping from the mass matrix) every window: the stage's dearest steady state.
    config.gain_ramps.enabled = true;
    config.passivity.enabled = true;
    config.passivity.tank_initial_j = 0.1;
    config.passivity.tank_max_j = 1e6;
  }
  return config;
}

void submitVariantCommands(pipeline::Wrapper<CartesianCommand>& wrapper, const Variant& variant,
                           const std::string& wrapper_name, double run_s) {
  if (variant.force) {
    submitForceCommand(wrapper, wrapper_name);
  }
  if (variant.chunked) {
    // The host's clock is the controller's here: 0 at activation.
    const pipeline::Verdict verdict =
        wrapper.submitChunk(benchChunk(wrapper.measuredPose(), run_s, wrapper.dof()), 0.0);
    if (!verdict.accepted) {
      throw std::runtime_error(wrapper_name +
                               ": the benchmark's chunk was refused: " + verdict.message);
    }
  }
}

}  // namespace comply::host::bench
