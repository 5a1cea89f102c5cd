#include "comply/hardware/control_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace comply::hardware {
namespace {

using SteadyClock = std::chrono::steady_clock;

double secondsBetween(SteadyClock::time_point from, SteadyClock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

}  // namespace

ControlLoop::ControlLoop(HardwareInterface& hardware, CycleController& controller, LoopClock& clock,
                         LoopOptions options)
    : hardware_(hardware), controller_(controller), clock_(clock), options_(options) {
  if (!(std::isfinite(options_.period_s) && options_.period_s > 0.0)) {
    throw std::invalid_argument("control loop: the period must be a positive number of seconds");
  }
  const int dof = controller_.dof();
  if (hardware_.dof() != dof || dof < 1 || dof > kMaxDof) {
    throw std::invalid_argument("control loop: the controller has " + std::to_string(dof) +
                                " joints, the hardware " + std::to_string(hardware_.dof()));
  }
  const OutputMode mode = controller_.outputMode();
  if (!hardware_.accepts(mode)) {
    std::string accepted;
    for (const auto& [candidate, name] : kOutputModeNames) {
      if (hardware_.accepts(candidate)) {
        accepted += (accepted.empty() ? "" : ", ") + std::string(name);
      }
    }
    throw std::invalid_argument(
        "control loop: the controller's output.mode is " + std::string(toString(mode)) +
        " but the hardware's drives take only " + (accepted.empty() ? "nothing" : accepted) +
        "; set output.mode to one of them");
  }
  state_ = JointState::zero(dof);
  command_.resize(dof);
  command_.mode = mode;
  start_s_ = clock_.now();
}

double ControlLoop::nextCycleTime() const noexcept {
  return start_s_ + static_cast<double>(next_index_) * options_.period_s;
}

bool ControlLoop::runOnce() {
  if (stop_requested_.load(std::memory_order_relaxed)) {
    return false;
  }
  if (next_index_ == 0) {
    // The schedule starts with the first cycle, not when the loop was built: the host's set-up
    // in between is no backlog to catch up on.
    start_s_ = clock_.now();
  }
  const double scheduled_s = nextCycleTime();
  if (options_.warm_ahead_s > 0.0 && stats_.cycles > 0 && clock_.passesByItself()) {
    clock_.waitUntil(scheduled_s - options_.warm_ahead_s);
    controller_.warm(state_);
    while (clock_.now() < scheduled_s) {
      // Spinning, not sleeping: a sleep would hand the core, and the caches just warmed, away.
    }
  }
  clock_.waitUntil(scheduled_s);
  const double start_lateness_s = clock_.lateness(scheduled_s);
  if (observer_ != nullptr) {
    observer_->beforeCycle(next_index_, scheduled_s - start_s_);
  }

  CycleRecord record;
  record.index = next_index_++;
  record.time_s = scheduled_s - start_s_;
  record.period_s = options_.period_s;
  record.start_lateness_s = start_lateness_s;
  const auto compute_start = SteadyClock::now();
  if (hardware_.read(state_)) {
    state_.wrench_valid = hardware_.readWrench(state_.wrench);
    state_.sequence_valid = hardware_.readSequence(state_.sequence);
    state_.robot_stop = hardware_.robotStop();
    const auto controller_start = SteadyClock::now();
    record.wrote = controller_.cycle(state_, options_.period_s, command_);
    record.controller_s = secondsBetween(controller_start, SteadyClock::now());
    double allowed_force_n = 0.0;
    double allowed_torque_n_m = 0.0;
    if (controller_.contactAllowance(allowed_force_n, allowed_torque_n_m)) {
      hardware_.allowContact(allowed_force_n, allowed_torque_n_m);
    }
    if (record.wrote && !hardware_.writeCommand(command_)) {
      ++stats_.write_failures;
    }
    if (record.wrote && controller_.wantsHold()) {
      record.held = hardware_.hold();
      stats_.held_cycles += record.held ? 1 : 0;
    }
    // No output (the controller is inactive): the robot holds, rather than keep the last torque.
    if (!record.wrote) {
      record.held = hardware_.hold();
      stats_.held_cycles += record.held ? 1 : 0;
    }
  } else {
    ++stats_.read_failures;
  }
  record.compute_s = secondsBetween(compute_start, SteadyClock::now());
  // Its deadline is the next cycle's start: a cycle that started late (a stall of the thread
  // before it, wherever it was) misses it with less computing than a whole period.
  record.overrun = std::max(record.start_lateness_s, 0.0) + record.compute_s > options_.period_s;
  record.state = &state_;
  record.torque = lastTorque();
  record.command = &command_;

  ++stats_.cycles;
  stats_.overruns += record.overrun ? 1 : 0;
  stats_.max_compute_s = std::max(stats_.max_compute_s, record.compute_s);
  stats_.max_start_lateness_s = std::max(stats_.max_start_lateness_s, record.start_lateness_s);
  if (observer_ != nullptr) {
    observer_->afterCycle(record);
  }
  return true;
}

LoopStats ControlLoop::run() {
  while ((options_.cycles == 0 || stats_.cycles < options_.cycles) && runOnce()) {
  }
  return stats_;
}

}  // namespace comply::hardware
