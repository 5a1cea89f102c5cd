// The emulated controller's cycle: comply's program applied from the registers, the plant
// stepped, the safety limit checked, the variables sent (ur_emulator.hpp).

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "comply/hardware/loop_clock.hpp"
#include "emulator_impl.hpp"

namespace comply::ur {
namespace {

/// A wake-up this late [s] is the host's stall, not a client's delay (awaitAnswer).
constexpr double kStallS = 0.5e-3;
/// The most stall time [s] one answer's wait makes up for.
constexpr double kMostStalledS = 0.1;
/// A long wait for an answer looks at the connections this often [s].
constexpr double kWaitSliceS = 0.01;

std::array<double, 6> sixOf(const JointVector& vector) {
  std::array<double, 6> six{};
  for (int i = 0; i < 6 && i < vector.size(); ++i) {
    six[static_cast<std::size_t>(i)] = vector[i];
  }
  return six;
}

}  // namespace

void UrEmulator::Impl::runCycles(const std::stop_token& stop) {
  const double period_s = options_.period_s;
  hardware::WallClock clock;  // an absolute deadline per cycle: no drift
  double next_s = clock.now();
  while (!stop.stop_requested()) {
    awaitAnswer();
    {
      const std::lock_guard lock(mutex_);
      cycle();
    }
    next_s += period_s;
    // A controller's cycle does not stall; this thread does, on a busy host. A cycle late by
    // less than a period starts at once (the rate stays 500 Hz); the cycles a longer stall missed
    // are not caught up in a burst, which would send the client packages back to back.
    const double now_s = clock.now();
    if (now_s - next_s > period_s) {
      next_s = now_s;
    }
    clock.waitUntil(next_s);
  }
}

void UrEmulator::Impl::awaitAnswer() {
  // A controller's cycle does not slip: a client always has one period from a package to its
  // answer. This thread's wake-ups do slip on a busy host; so that a late wake-up (which sent
  // the last package late) is not counted against the client, the cycle waits for the answer
  // until one period after the package went out (answer_wait_s, when longer).
  std::string answer_register;
  std::int32_t expected = 0;
  double last_send_s = 0.0;
  {
    const std::lock_guard lock(mutex_);
    if (!running_ || !armed_ || cycle_ == 0 || !sent_[static_cast<std::size_t>(cycle_)]) {
      return;
    }
    answer_register = names_.answer;
    expected = static_cast<std::int32_t>(cycle_);
    last_send_s = last_send_s_;
  }
  const double wait_s = std::max(options_.period_s, options_.answer_wait_s);
  const double give_up_s = hardware::monotonicSeconds() + wait_s + 2.0 * options_.period_s;
  double stalled_s = 0.0;
  for (;;) {
    // From when the package's bytes left: the I/O thread writes it a little after the cycle
    // queued it, or (stalled) not yet, when the period has not started. Time this thread was
    // kept from running while it waited (a wake-up far past its timeout: the host stalled it,
    // and the client with it, most likely) is added.
    const double written_s = rtde_.lastOutputWritten();
    const double left_at_s = written_s >= last_send_s ? written_s : hardware::monotonicSeconds();
    const double on_time_s = left_at_s + options_.period_s + stalled_s;
    const double deadline_s = std::min(left_at_s + wait_s, give_up_s) + stalled_s;
    const std::uint64_t seen = rtde_.inputPackages();
    const auto inputs = rtde_.inputs();
    const auto found = inputs.find(answer_register);
    const double now_s = hardware::monotonicSeconds();
    if (found != inputs.end() && std::holds_alternative<std::int32_t>(found->second) &&
        std::get<std::int32_t>(found->second) == expected) {
      if (now_s > on_time_s) {
        const std::lock_guard lock(mutex_);
        ++stats_.late;  // in, but after a controller's cycle would have read its registers
      }
      return;
    }
    // No client left (a cable pulled): nothing to wait for.
    if (now_s >= deadline_s || rtde_.connections() == 0) {
      return;
    }
    const double slice_end_s = std::min(deadline_s, now_s + kWaitSliceS);
    if (!rtde_.awaitInputs(seen, slice_end_s - now_s)) {
      const double overslept_s = hardware::monotonicSeconds() - slice_end_s;
      if (overslept_s >= kStallS && stalled_s <= kMostStalledS) {
        stalled_s += overslept_s;
      }
    }
  }
}

void UrEmulator::Impl::cycle() {
  startPendingProgram();
  for (const auto& [name, value] : rtde_.inputs()) {
    registers_[name] = value;
  }
  if (running_ && safety_mode_ == 1) {
    applyProgram();
  } else {
    plant_->hold();
    servo_following_ = false;
  }
  plant_->step();
  plant_->read(measured_);
  checkSafety();
  sendOutputs();
  ++cycle_;
}

void UrEmulator::Impl::startPendingProgram() {
  if (!pending_) {
    return;
  }
  if (safety_mode_ != 1) {
    stats_.last_program_error = "the program cannot start: the robot is protectively stopped";
    pending_.reset();
    return;
  }
  program_ = *pending_;
  pending_.reset();
  const OutputMode actuation = program_.mode;
  if (actuation != plant_mode_) {
    buildPlant(actuation);  // the arm at rest where it was, with the drives the program uses
  }
  running_ = true;
  program_flag_ = program_.instance;
  armed_ = false;
  quiet_s_ = 0.0;
  names_ = ProgramRegisters(program_.register_offset);
  last_answer_ = intRegister(names_.answer);
  ++stats_.programs;
}

void UrEmulator::Impl::applyProgram() {
  const std::int32_t answer = intRegister(names_.answer);
  if (answer != last_answer_) {
    // Packages sent between the last answer and this one that no answer named.
    const std::int64_t end =
        std::min<std::int64_t>(answer, static_cast<std::int64_t>(sent_.size()));
    for (std::int64_t index = std::int64_t{last_answer_} + 1; armed_ && index < end; ++index) {
      if (index >= 0 && sent_[static_cast<std::size_t>(index)]) {
        ++stats_.missed;
      }
    }
    last_answer_ = answer;
    armed_ = true;
    quiet_s_ = 0.0;
    ++stats_.answered;
  } else {
    quiet_s_ += program_.period_s;
  }
  // The package of the last cycle is numbered cycle_: its answer is due by now.
  const auto last_package = static_cast<std::size_t>(cycle_);
  if (armed_ && answer != static_cast<std::int32_t>(cycle_) && last_package < sent_.size() &&
      sent_[last_package]) {
    ++stats_.late;
  }
  if (armed_ && quiet_s_ > program_.watchdog_s) {
    ++stats_.watchdog_stops;
    stopProgram(-program_.instance);
    plant_->hold();
    servo_following_ = false;
    return;
  }
  applied_ = answer;
  std::array<double, 6> values{};
  for (int joint = 0; joint < 6; ++joint) {
    values[static_cast<std::size_t>(joint)] =
        doubleRegister(names_.target[static_cast<std::size_t>(joint)]);
  }
  command(intRegister(names_.drive), values);
}

void UrEmulator::Impl::command(int drive, const std::array<double, 6>& values) {
  bool finite = true;
  for (const double value : values) {
    finite = finite && std::isfinite(value);
  }
  if (drive != 1 || !finite) {
    plant_->hold();  // stopj, or a script that would stop on a bad number: the arm stands
    servo_following_ = false;
    return;
  }
  ActuatorCommand drives;
  drives.mode = program_.mode;
  drives.resize(6);
  for (int joint = 0; joint < 6; ++joint) {
    const double value = values[static_cast<std::size_t>(joint)];
    if (program_.mode == OutputMode::kPosition) {
      // servoj follows the targets as a trajectory: its velocity is theirs, from one cycle's
      // target to the next (none for the first after a stop).
      const auto j = static_cast<std::size_t>(joint);
      drives.position[joint] = value;
      drives.velocity[joint] =
          servo_following_ ? (value - last_target_[j]) / program_.period_s : 0.0;
      last_target_[j] = value;
    } else if (program_.mode == OutputMode::kVelocity) {
      drives.velocity[joint] = value;
    } else {
      // direct_torque: on top of the controller's own gravity and Coriolis compensation.
      const int dof = dof_address_[static_cast<std::size_t>(joint)];
      drives.effort[joint] = value + plant_->mujocoData().qfrc_bias[dof];
    }
  }
  (void)plant_->writeCommand(drives);
  servo_following_ = program_.mode == OutputMode::kPosition;
}

void UrEmulator::Impl::stopProgram(std::int32_t flag) {
  running_ = false;
  program_flag_ = flag;
}

void UrEmulator::Impl::checkSafety() {
  if (options_.protective_stop_force_n > 0.0 &&
      plant_->toolContactWrench().head<3>().norm() > options_.protective_stop_force_n) {
    protectiveStopLocked();
  }
}

void UrEmulator::Impl::sendOutputs() {
  const std::size_t index = static_cast<std::size_t>(cycle_) + 1;
  if (sent_.size() <= index) {
    sent_.resize(index + 1, false);
  }
  if (drop_ > 0) {
    --drop_;
    ++stats_.dropped;
    ++stats_.cycles;
    return;
  }
  sent_[index] = true;
  ++stats_.cycles;
  last_send_s_ = hardware::monotonicSeconds();
  Vector6d wrench = Vector6d::Zero();
  if (plant_->readWrench(wrench)) {
    wrench -= wrench_tare_;  // the controller takes the payload's weight off
  }
  const Eigen::Isometry3d tcp = plant_->tcpPose();
  const Eigen::AngleAxisd rotation(tcp.rotation());
  const Eigen::Vector3d rotation_vector = rotation.angle() * rotation.axis();
  const std::array<double, 6> pose{tcp.translation().x(), tcp.translation().y(),
                                   tcp.translation().z(), rotation_vector.x(),
                                   rotation_vector.y(),   rotation_vector.z()};
  const auto runtime = static_cast<std::uint32_t>(running_ ? 2 : 1);
  const std::map<std::string, RtdeValue> variables{
      {"timestamp", static_cast<double>(cycle_) * options_.period_s},
      {"actual_q", sixOf(measured_.position)},
      {"actual_qd", sixOf(measured_.velocity)},
      {"actual_current_as_torque", sixOf(measured_.effort)},
      {"actual_TCP_force",
       std::array<double, 6>{wrench[0], wrench[1], wrench[2], wrench[3], wrench[4], wrench[5]}},
      {"actual_TCP_pose", pose},
      {"robot_mode", std::int32_t{7}},
      {"safety_mode", safety_mode_},
      {"safety_status", safety_mode_},
      {"runtime_state", runtime},
      {"speed_scaling", 1.0},
      {"target_speed_fraction", 1.0},
      {names_.applied, applied_},
      {names_.flag, program_flag_}};
  rtde_.sendOutputs(variables);
}

ProgramRegisters::ProgramRegisters(int offset)
    : answer("input_int_register_" + std::to_string(offset)),
      drive("input_int_register_" + std::to_string(offset + 1)),
      applied("output_int_register_" + std::to_string(offset)),
      flag("output_int_register_" + std::to_string(offset + 1)) {
  for (int joint = 0; joint < 6; ++joint) {
    target[static_cast<std::size_t>(joint)] =
        "input_double_register_" + std::to_string(offset + joint);
  }
}

std::int32_t UrEmulator::Impl::intRegister(const std::string& name) const {
  const auto found = registers_.find(name);
  return found != registers_.end() && std::holds_alternative<std::int32_t>(found->second)
             ? std::get<std::int32_t>(found->second)
             : 0;
}

double UrEmulator::Impl::doubleRegister(const std::string& name) const {
  const auto found = registers_.find(name);
  return found != registers_.end() && std::holds_alternative<double>(found->second)
             ? std::get<double>(found->second)
             : 0.0;
}

}  // namespace comply::ur
