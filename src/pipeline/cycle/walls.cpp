// Stage "walls" and the barrier (virtual_walls.hpp): the law's reference kept inside the walls
// and boxes before the law runs, and a TCP approaching a wall braked after the governor, so that
// the governor's scaling never takes the brake's force back. Without walls (or with a joint law)
// each costs one branch.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::limitToWalls() noexcept {
  walls_active_ = false;
  // The box of the command in force, whatever stage rewrote the reference since (a chunk plays
  // into it, so its box stays; workspace_intake.hpp checked it).
  if (const auto* in_force = std::get_if<comply_cartesian_command>(&active_)) {
    walls_.commandBox(in_force->workspace_min, in_force->workspace_max);
  }
  if (!walls_.enabled()) {
    return;
  }
  const auto* in = std::get_if<comply_cartesian_command>(&forcedBus());
  auto* out = std::get_if<comply_cartesian_command>(&walls_bus_);
  if (in == nullptr || out == nullptr) {
    return;
  }
  walls_active_ = walls_.limitReference(*in, data_.tip_position, *out);
  if (walls_active_) {
    diagnostics_.wall_reference_hits.fetch_add(1, std::memory_order_relaxed);
  }
}

void Controller::brakeAtWalls() noexcept {
  walled_ = false;
  if (!walls_.enabled()) {
    return;
  }
  walled_ = walls_.brake(data_, tcp_twist_, dof_, torque_);
  if (walled_) {
    diagnostics_.wall_brake_hits.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace comply::pipeline
