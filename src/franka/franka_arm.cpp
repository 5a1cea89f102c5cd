// A Franka arm through an FCI client (franka_arm.hpp).

#include "comply/franka/franka_arm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "comply/franka/franka_errors.hpp"
#include "comply/hardware/backend.hpp"

namespace comply::franka {
namespace {

constexpr const char* kLinkLost =
    "the link to the Franka robot is lost: no state within link_timeout_s, or its connection "
    "closed (the network, the robot's FCI, or the robot switched off); the robot stops itself "
    "without comply's torques";
constexpr const char* kControlEnded =
    "the robot ended comply's torque control (another client, Desk or a stop request): "
    "reset to start it again";

constexpr double kRobotPeriodS = 0.001;

// The requests of other threads (recovery_).
constexpr int kNone = 0;
constexpr int kAsked = 1;
constexpr int kDone = 2;
constexpr int kFailed = 3;

// thresholds_request_.
constexpr int kNoRequest = 0;
constexpr int kWriting = 1;
constexpr int kWaiting = 2;

}  // namespace

fci::CollisionThresholds frankaCollisionThresholds(double collision_torque_n_m,
                                                   double collision_force_n,
                                                   double collision_flange_torque_n_m) {
  if (collision_flange_torque_n_m < 0.0) {
    collision_flange_torque_n_m = 0.1 * collision_force_n;
  }
  if (!(collision_torque_n_m > 0.0) || !(collision_force_n > 0.0) ||
      !std::isfinite(collision_torque_n_m) || !std::isfinite(collision_force_n) ||
      !std::isfinite(collision_flange_torque_n_m)) {
    throw hardware::BackendError("collision thresholds must be positive and finite (got " +
                                 std::to_string(collision_torque_n_m) + " N m, " +
                                 std::to_string(collision_force_n) + " N)");
  }
  fci::CollisionThresholds thresholds;
  const double contact_torque = 0.8 * collision_torque_n_m;
  thresholds.torque_contact_acceleration.fill(contact_torque);
  thresholds.torque_contact_nominal.fill(contact_torque);
  thresholds.torque_collision_acceleration.fill(collision_torque_n_m);
  thresholds.torque_collision_nominal.fill(collision_torque_n_m);
  for (std::size_t axis = 0; axis < 6; ++axis) {
    const double collision = axis < 3 ? collision_force_n : collision_flange_torque_n_m;
    thresholds.force_contact_acceleration[axis] = 0.8 * collision;
    thresholds.force_contact_nominal[axis] = 0.8 * collision;
    thresholds.force_collision_acceleration[axis] = collision;
    thresholds.force_collision_nominal[axis] = collision;
  }
  return thresholds;
}

FrankaArm::FrankaArm(std::unique_ptr<FrankaSession> session, FrankaArmOptions options)
    : session_(std::move(session)), options_(options), base_(options.collision) {
  if (!session_) {
    throw hardware::BackendError("a Franka arm needs a session to its robot");
  }
  if (const std::string why = session_->setCollisionThresholds(options_.collision); !why.empty()) {
    throw hardware::BackendError("the Franka robot refused the collision thresholds: " + why);
  }
  if (!awaitSample()) {
    throw hardware::BackendError(
        std::string("no state from the Franka robot: ") +
        (session_->failure() != nullptr ? session_->failure() : "none within link_timeout_s"));
  }
}

FrankaArm::~FrankaArm() {
  if (controlling_) {
    try {
      (void)session_->stopTorqueControl();  // the robot holds the arm where it is
    } catch (...) {
    }
  }
}

bool FrankaArm::awaitSample() noexcept {
  carryOutRequests();
  if (wants_control_ && !controlling_ && stop_ == nullptr) {
    startControl();
  }
  wants_control_ = false;
  FrankaSample next;
  const bool started_on_fresh = started_;
  if (started_) {
    next = started_on_;  // the state the torque control started on: the first torque answers it
    fresh_ = true;
    started_ = false;
  } else {
    // Once the link is lost, a cycle waits one robot period for it, not the whole timeout: the
    // loop goes on at the robot's rate (holding, in FAULT) and its duration stays its own.
    const bool lost = stop_ == kLinkLost;
    fresh_ = session_->read(next, lost ? kRobotPeriodS : options_.link_timeout_s);
  }
  if (!fresh_) {
    controlling_ = false;  // the robot ends a torque control it gets no torques for
    noteStop(kLinkLost);
    return false;
  }
  // States missed while comply's torques drive the arm (outside, the robot holds it: no loss).
  if (sample_valid_ && controlling_ && !started_on_fresh && next.time_ms > sample_.time_ms + 1) {
    skipped_.fetch_add(next.time_ms - sample_.time_ms - 1, std::memory_order_relaxed);
  }
  sample_ = next;
  sample_valid_ = true;
  states_.fetch_add(1, std::memory_order_relaxed);
  if (sample_.command_success_rate < worst_success_rate_.load(std::memory_order_relaxed) &&
      controlling_) {
    worst_success_rate_.store(sample_.command_success_rate, std::memory_order_relaxed);
  }
  const char* stop = stopText(sample_.errors, sample_.robot_mode);
  if (stop == nullptr && controlling_ && !sample_.torque_control) {
    // Ended from outside comply: by a reflex (its flags name it) or a stop request (none).
    const bool named =
        std::any_of(sample_.last_motion_errors.begin(), sample_.last_motion_errors.end(),
                    [](bool flag) { return flag; });
    stop = named ? stopText(sample_.last_motion_errors, fci::RobotMode::kReflex) : kControlEnded;
  }
  if (stop != nullptr) {
    controlling_ = controlling_ && sample_.torque_control;
  }
  noteStop(stop);
  return true;
}

void FrankaArm::noteStop(const char* stop) noexcept {
  if (stop != nullptr && stop_ == nullptr) {
    stops_.fetch_add(1, std::memory_order_relaxed);
  }
  // A torque control the robot ended stays a stop until a recovery or a new start clears it.
  if (stop == nullptr && stop_ == kControlEnded) {
    return;
  }
  stop_ = stop;
  stopped_.store(stop != nullptr, std::memory_order_release);
}

void FrankaArm::carryOutRequests() noexcept {
  if (recovery_.load(std::memory_order_acquire) == kAsked) {
    try {
      if (controlling_) {
        controlling_ = false;
        (void)session_->stopTorqueControl();
      }
      recovery_error_ = session_->recover();
    } catch (...) {
      recovery_error_ = "the recovery failed";
    }
    if (recovery_error_.empty()) {
      recoveries_.fetch_add(1, std::memory_order_relaxed);
      if (stop_ == kControlEnded || stop_ == kLinkLost) {
        stop_ = nullptr;  // recovered: the next state decides
      }
    }
    recovery_.store(recovery_error_.empty() ? kDone : kFailed, std::memory_order_release);
  }
  if (thresholds_request_.load(std::memory_order_acquire) == kWaiting) {
    base_ = thresholds_;
    thresholds_request_.store(kNoRequest, std::memory_order_release);
    applyThresholds(allowedThresholds());
  } else if (contact_pending_) {
    applyThresholds(allowedThresholds());
  }
  contact_pending_ = false;
}

void FrankaArm::applyThresholds(const fci::CollisionThresholds& thresholds) noexcept {
  const bool was_controlling = controlling_;
  try {
    if (was_controlling) {
      controlling_ = false;
      (void)session_->stopTorqueControl();  // the robot takes thresholds only between motions
    }
    if (session_->setCollisionThresholds(thresholds).empty()) {
      threshold_changes_.fetch_add(1, std::memory_order_relaxed);
    }
  } catch (...) {
  }
  if (was_controlling && stop_ == nullptr) {
    startControl();
  }
}

fci::CollisionThresholds FrankaArm::allowedThresholds() const {
  // The base, each raised to contact_margin x the contact comply lets through.
  fci::CollisionThresholds thresholds = base_;
  const double margin = options_.contact_margin;
  const auto raise = [](std::array<double, 7>& values, double at_least) {
    for (double& value : values) {
      value = std::max(value, at_least);
    }
  };
  raise(thresholds.torque_collision_acceleration,
        margin * allowed_force_n_ * options_.contact_lever_m);
  raise(thresholds.torque_collision_nominal, margin * allowed_force_n_ * options_.contact_lever_m);
  raise(thresholds.torque_contact_acceleration,
        0.8 * margin * allowed_force_n_ * options_.contact_lever_m);
  raise(thresholds.torque_contact_nominal,
        0.8 * margin * allowed_force_n_ * options_.contact_lever_m);
  for (std::size_t axis = 0; axis < 6; ++axis) {
    const double allowed = margin * (axis < 3 ? allowed_force_n_ : allowed_torque_n_m_);
    thresholds.force_collision_acceleration[axis] =
        std::max(thresholds.force_collision_acceleration[axis], allowed);
    thresholds.force_collision_nominal[axis] =
        std::max(thresholds.force_collision_nominal[axis], allowed);
    thresholds.force_contact_acceleration[axis] =
        std::max(thresholds.force_contact_acceleration[axis], 0.8 * allowed);
    thresholds.force_contact_nominal[axis] =
        std::max(thresholds.force_contact_nominal[axis], 0.8 * allowed);
  }
  return thresholds;
}

void FrankaArm::allowContact(double force_n, double torque_n_m) noexcept {
  if (!std::isfinite(force_n) || !std::isfinite(torque_n_m)) {
    return;
  }
  const auto changed = [](double now, double before) {
    return std::abs(now - before) > 0.1 * std::max(std::abs(before), 1e-9);
  };
  if (changed(force_n, allowed_force_n_) || changed(torque_n_m, allowed_torque_n_m_)) {
    allowed_force_n_ = force_n;
    allowed_torque_n_m_ = torque_n_m;
    contact_pending_ = true;
  }
}

bool FrankaArm::read(JointState& state) noexcept {
  if (!sample_valid_) {
    return false;
  }
  state.position.resize(7);
  state.velocity.resize(7);
  state.effort.resize(7);
  for (int joint = 0; joint < 7; ++joint) {
    const auto j = static_cast<std::size_t>(joint);
    state.position[joint] = sample_.q[j];
    state.velocity[joint] = sample_.dq[j];
    state.effort[joint] = sample_.tau_J[j];
  }
  return true;
}

bool FrankaArm::readWrench(Vector6d& wrench) noexcept {
  if (!sample_valid_ || !fresh_) {
    return false;
  }
  // The robot reports what the arm exerts on its surroundings; comply's wrist-sensor convention
  // is the wrench the surroundings exert on the tool: the opposite.
  for (int axis = 0; axis < 6; ++axis) {
    wrench[axis] = -sample_.O_F_ext_hat_K[static_cast<std::size_t>(axis)];
  }
  return wrench.allFinite();
}

bool FrankaArm::readSequence(std::uint64_t& sequence) noexcept {
  if (!sample_valid_) {
    return false;
  }
  sequence = sample_.time_ms;
  return true;
}

bool FrankaArm::write(std::span<const double> torque) noexcept {
  if (torque.size() != 7 || stop_ != nullptr || !fresh_) {
    return false;
  }
  if (!controlling_) {
    // Started at the next sample, unless this cycle also asks for the robot's hold (a FAULT
    // at rest writes its hold torque and asks for the brakes every cycle).
    wants_control_ = true;
    return true;
  }
  return session_->writeTorque(std::span<const double, 7>(torque.data(), 7));
}

void FrankaArm::startControl() noexcept {
  std::string why;
  try {
    why = session_->startTorqueControl(started_on_);
  } catch (...) {
    why = "the torque control could not start";
  }
  if (why.empty()) {
    controlling_ = true;
    started_ = true;
    controls_.fetch_add(1, std::memory_order_relaxed);
  }
}

bool FrankaArm::hold() noexcept {
  wants_control_ = false;
  if (controlling_) {
    try {
      (void)session_->stopTorqueControl();
    } catch (...) {
    }
    controlling_ = false;
  }
  return true;  // the robot holds the arm itself outside a torque control
}

std::string FrankaArm::recover() {
  if (!stopped_.load(std::memory_order_acquire)) {
    return {};
  }
  int expected = kNone;
  if (!recovery_.compare_exchange_strong(expected, kAsked, std::memory_order_acq_rel)) {
    return "a recovery is already under way";
  }
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.recovery_timeout_s);
  int outcome = kAsked;
  while ((outcome = recovery_.load(std::memory_order_acquire)) == kAsked) {
    if (std::chrono::steady_clock::now() > deadline) {
      // The control thread takes it on when it next runs; this reset is refused meanwhile.
      return "the robot's error recovery did not finish within " +
             std::to_string(options_.recovery_timeout_s) + " s";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::string why = outcome == kFailed ? recovery_error_ : std::string();
  recovery_.store(kNone, std::memory_order_release);
  // The next states show whether the robot runs again (the reset's own check).
  const auto settle = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  while (why.empty() && stopped_.load(std::memory_order_acquire) &&
         std::chrono::steady_clock::now() < settle) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return why;
}

bool FrankaArm::requestCollisionThresholds(const fci::CollisionThresholds& thresholds) noexcept {
  int idle = kNoRequest;
  if (!thresholds_request_.compare_exchange_strong(idle, kWriting, std::memory_order_acquire)) {
    return false;  // another request is being written or waits for the control thread
  }
  thresholds_ = thresholds;
  thresholds_request_.store(kWaiting, std::memory_order_release);
  return true;
}

double FrankaArm::sampleTime() const noexcept {
  return static_cast<double>(sample_.time_ms) * 1e-3;
}

FrankaArmStats FrankaArm::stats() const noexcept {
  FrankaArmStats stats;
  stats.states = states_.load(std::memory_order_relaxed);
  stats.skipped = skipped_.load(std::memory_order_relaxed);
  stats.controls = controls_.load(std::memory_order_relaxed);
  stats.stops = stops_.load(std::memory_order_relaxed);
  stats.recoveries = recoveries_.load(std::memory_order_relaxed);
  stats.threshold_changes = threshold_changes_.load(std::memory_order_relaxed);
  stats.worst_success_rate = worst_success_rate_.load(std::memory_order_relaxed);
  return stats;
}

std::string FrankaArm::summary() const {
  const FrankaArmStats s = stats();
  return "Franka link: " + std::to_string(s.states) + " states, " + std::to_string(s.skipped) +
         " skipped, " + std::to_string(s.controls) + " torque controls started, " +
         std::to_string(s.stops) + " stops, " + std::to_string(s.recoveries) + " recoveries, " +
         std::to_string(s.threshold_changes) + " threshold changes, lowest command success rate " +
         std::to_string(s.worst_success_rate) + " (" + session_->description() + ")";
}

void FrankaClock::waitUntil(double time_s) noexcept {
  (void)time_s;  // the robot's states pace the loop
  (void)arm_.awaitSample();
}

double FrankaClock::lateness(double time_s) noexcept {
  (void)time_s;
  // From the state's arrival; a cycle without a new state (the link lost) is late for none.
  return arm_.sampleFresh() ? hardware::monotonicSeconds() - arm_.sampleArrival() : 0.0;
}

}  // namespace comply::franka
