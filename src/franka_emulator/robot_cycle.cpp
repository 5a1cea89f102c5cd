// The emulated robot's 1 ms cycle: the client's command taken, the motion applied, the plant
// stepped, the reflexes checked, the state sent (franka_emulator.hpp).

#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cmath>

#include "comply/franka/franka_errors.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/model/update.hpp"
#include "emulator_impl.hpp"

namespace comply::franka {
namespace {

constexpr double kPeriodS = 0.001;
constexpr int kCommunicationConstraints = 25;  // the flag's index (franka_errors.hpp)
constexpr int kJointReflex = 6;
constexpr int kCartesianReflex = 7;

void putTransform(std::span<double> out, const Eigen::Isometry3d& transform) {
  const Eigen::Matrix4d& matrix = transform.matrix();
  std::copy(matrix.data(), matrix.data() + 16, out.begin());  // column-major, as on the wire
}

}  // namespace

void FrankaEmulator::Impl::runCycles(const std::stop_token& stop) {
  hardware::WallClock clock;  // an absolute deadline per cycle: no drift
  double next_s = clock.now();
  while (!stop.stop_requested()) {
    receiveCommands();
    {
      const std::lock_guard lock(mutex_);
      cycle();
    }
    next_s += kPeriodS;
    // A stall of this thread is not caught up in a burst of states.
    const double now_s = clock.now();
    if (now_s - next_s > kPeriodS) {
      next_s = now_s;
    }
    clock.waitUntil(next_s);
  }
}

void FrankaEmulator::Impl::receiveCommands() {
  answered_ = false;
  late_ = false;
  bool in_motion = false;
  {
    const std::lock_guard lock(mutex_);
    in_motion = motion_.has_value() && streaming_;
  }
  const double give_up_s = last_send_s_ + std::max(options_.answer_wait_s, 0.0);
  bool waited = false;  // the answer was not in when the cycle began
  for (;;) {
    while (true) {
      const ssize_t got = ::recv(udp_, datagram_.data(), datagram_.size(), MSG_DONTWAIT);
      if (got < 0) {
        break;
      }
      if (got != static_cast<ssize_t>(fci::kCommandBytes)) {
        continue;  // not a command
      }
      const fci::RobotCommandMessage command =
          fci::getRobotCommand(std::span<const std::uint8_t, fci::kCommandBytes>(datagram_));
      if (command.message_id == last_sent_id_) {
        command_ = command;
        answered_ = true;
        // Late: waited for past the cycle's period (a command already in when a stalled cycle
        // began is not the client's lateness).
        late_ = waited && hardware::monotonicSeconds() > last_send_s_ + kPeriodS;
      }
    }
    const double now_s = hardware::monotonicSeconds();
    if (answered_ || !in_motion || now_s >= give_up_s) {
      return;
    }
    waited = true;
    pollfd readable{udp_, POLLIN, 0};
    (void)::poll(&readable, 1, std::max(1, static_cast<int>((give_up_s - now_s) * 1e3)));
  }
}

void FrankaEmulator::Impl::cycle() {
  ++time_ms_;
  if (mode_ == fci::RobotMode::kAutomaticErrorRecovery && time_ms_ >= recovery_end_ms_) {
    mode_ = fci::RobotMode::kIdle;
    errors_.fill(false);
    ++stats_.recoveries;
    if (recovery_id_) {
      respond(fci::Command::kAutomaticErrorRecovery, *recovery_id_, 0);
      recovery_id_.reset();
    }
  }
  if (motion_) {
    bool answered = answered_;
    if (answered && lose_ > 0) {
      --lose_;
      answered = false;  // lost on the way
    }
    success_[success_at_] = answered;
    success_at_ = (success_at_ + 1) % success_.size();
    if (answered) {
      ++stats_.answered;
      stats_.late += late_ ? 1 : 0;
      lost_run_ = 0;
    } else {
      ++stats_.lost;
      ++lost_run_;
      stats_.longest_lost_run = std::max(stats_.longest_lost_run, lost_run_);
    }
    if (lost_run_ >= static_cast<std::uint64_t>(options_.lost_in_a_row_limit)) {
      enterReflex(kCommunicationConstraints);
    } else if (answered && command_.motion_finished) {
      endMotion(fci::MoveStatus::kSuccess);
    } else {
      // A lost command: the robot goes on with the last one it has.
      applyMotion(&command_);
    }
  }
  if (pending_motion_ && mode_ == fci::RobotMode::kIdle) {
    // From the next state on: the last one went out before the motion, nobody answers it.
    startMotion();
  }
  if (!motion_) {
    holdArm();
  }
  plant_->step();
  plant_->read(measured_);
  checkReflexes();
  sendState();
}

void FrankaEmulator::Impl::startMotion() {
  motion_ = pending_motion_;
  pending_motion_.reset();
  mode_ = fci::RobotMode::kMove;
  reflex_reason_.fill(false);
  lost_run_ = 0;
  success_.fill(true);
  command_ = {};
  answered_ = false;
  commanded_torque_.fill(0.0);
  for (int joint = 0; joint < 7; ++joint) {
    target_q_[static_cast<std::size_t>(joint)] = measured_.position[joint];
  }
  command_.q_c = target_q_;
  ++stats_.motions;
}

void FrankaEmulator::Impl::endMotion(fci::MoveStatus status) {
  if (!motion_) {
    return;
  }
  const std::uint32_t id = motion_->id;
  motion_.reset();
  if (mode_ == fci::RobotMode::kMove) {
    mode_ = fci::RobotMode::kIdle;
  }
  holdArm();
  respond(fci::Command::kMove, id, static_cast<std::uint8_t>(status));
}

void FrankaEmulator::Impl::enterReflex(int error_index) {
  std::array<bool, fci::kErrorCount> flags{};
  flags[static_cast<std::size_t>(error_index)] = true;
  errors_ = flags;
  reflex_reason_ = flags;
  stats_.last_reflex = errorName(error_index);
  ++stats_.reflexes;
  const bool moving = motion_.has_value();
  mode_ = fci::RobotMode::kReflex;
  if (moving) {
    endMotion(fci::MoveStatus::kReflexAborted);
  }
  holdArm();
}

void FrankaEmulator::Impl::applyMotion(const fci::RobotCommandMessage* command) {
  // The model is at the state measured last (checkReflexes), the one these drives act from.
  ActuatorCommand drives;
  drives.mode = OutputMode::kJointPd;
  drives.resize(7);
  if (motion_->controller == fci::MoveController::kExternal) {
    for (int joint = 0; joint < 7; ++joint) {
      const auto j = static_cast<std::size_t>(joint);
      const double torque = std::isfinite(command->tau_J_d[j]) ? command->tau_J_d[j] : 0.0;
      commanded_torque_[j] = torque;
      drives.effort[joint] = torque + model_data_.gravity[joint];
    }
  } else {
    // The robot's joint impedance follows the client's motion generator.
    for (int joint = 0; joint < 7; ++joint) {
      const auto j = static_cast<std::size_t>(joint);
      if (motion_->generator == fci::MoveGenerator::kJointPosition) {
        target_q_[j] = command->q_c[j];
      } else {
        target_q_[j] += command->dq_c[j] * kPeriodS;
      }
      drives.position[joint] = target_q_[j];
      drives.velocity[joint] =
          motion_->generator == fci::MoveGenerator::kJointVelocity ? command->dq_c[j] : 0.0;
      drives.stiffness[joint] = joint_stiffness_[j];
      drives.damping[joint] = joint_damping_[j];
      drives.effort[joint] = model_data_.gravity[joint];
      commanded_torque_[j] = 0.0;
    }
  }
  (void)plant_->writeCommand(drives);
}

void FrankaEmulator::Impl::updateModel(model::Quantity quantities) {
  const auto joints = static_cast<std::size_t>(measured_.position.size());
  (void)model::update(model_, model_data_, {measured_.position.data(), joints},
                      {measured_.velocity.data(), joints}, quantities);
}

void FrankaEmulator::Impl::holdArm() {
  (void)plant_->hold();
  commanded_torque_.fill(0.0);
}

void FrankaEmulator::Impl::checkReflexes() {
  plant_->setExternalWrench(push_);
  external_wrench_ = plant_->toolContactWrench() + push_;
  // Once per cycle, at the new state: the reflexes' Jacobian, the state's pose, and the gravity
  // the next cycle's drives add.
  updateModel(model::Quantity::kJacobian | model::Quantity::kPose | model::Quantity::kGravity);
  external_torque_ = model_data_.jacobian.transpose() * external_wrench_;
  if (mode_ != fci::RobotMode::kMove) {
    return;
  }
  for (std::size_t axis = 0; axis < 6; ++axis) {
    if (std::abs(external_wrench_[static_cast<Eigen::Index>(axis)]) >
        collision_.force_collision_nominal[axis]) {
      enterReflex(kCartesianReflex);
      return;
    }
  }
  for (std::size_t joint = 0; joint < 7; ++joint) {
    if (std::abs(external_torque_[static_cast<Eigen::Index>(joint)]) >
        collision_.torque_collision_nominal[joint]) {
      enterReflex(kJointReflex);
      return;
    }
  }
}

void FrankaEmulator::Impl::sendState() {
  ++stats_.states;
  if (!streaming_) {
    return;
  }
  if (drop_ > 0) {
    --drop_;
    ++stats_.dropped;
    return;
  }
  fci::RobotStateMessage state;
  state.message_id = time_ms_;
  const auto put = [&](fci::StateField field, const auto& values) {
    const auto out = state.field(field);
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] = values[static_cast<Eigen::Index>(i)];
    }
  };
  Eigen::Matrix<double, 7, 1> target;
  for (int joint = 0; joint < 7; ++joint) {
    target[joint] =
        motion_ ? target_q_[static_cast<std::size_t>(joint)] : measured_.position[joint];
  }
  put(fci::StateField::kQ, measured_.position);
  put(fci::StateField::kTheta, measured_.position);
  put(fci::StateField::kDq, measured_.velocity);
  put(fci::StateField::kDtheta, measured_.velocity);
  put(fci::StateField::kTau_J, measured_.effort);
  put(fci::StateField::kTau_J_d, commanded_torque_);
  put(fci::StateField::kQ_d, target);
  // The robot's sign: what the arm exerts on its surroundings (franka_session.hpp).
  const Vector6d exerted = -external_wrench_;
  put(fci::StateField::kO_F_ext_hat_K, exerted);
  const Eigen::Matrix3d rotation = model_data_.tip_rotation;
  Vector6d in_tool;
  in_tool << rotation.transpose() * exerted.head<3>(), rotation.transpose() * exerted.tail<3>();
  put(fci::StateField::kK_F_ext_hat_K, in_tool);
  const Eigen::Matrix<double, 7, 1> exerted_torque = -external_torque_;
  put(fci::StateField::kTauExtHatFiltered, exerted_torque);
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
  tcp.linear() = rotation;
  tcp.translation() = model_data_.tip_position;
  putTransform(state.field(fci::StateField::kO_T_EE), tcp);
  putTransform(state.field(fci::StateField::kO_T_EE_d), tcp);
  putTransform(state.field(fci::StateField::kO_T_EE_c), tcp);
  putTransform(state.field(fci::StateField::kF_T_EE), Eigen::Isometry3d::Identity());
  putTransform(state.field(fci::StateField::kF_T_NE), Eigen::Isometry3d::Identity());
  putTransform(state.field(fci::StateField::kNE_T_EE), Eigen::Isometry3d::Identity());
  putTransform(state.field(fci::StateField::kEE_T_K), Eigen::Isometry3d::Identity());
  if (motion_) {
    state.generator = motion_->generator == fci::MoveGenerator::kJointPosition
                          ? fci::GeneratorMode::kJointPosition
                          : fci::GeneratorMode::kJointVelocity;
    state.controller = motion_->controller == fci::MoveController::kExternal
                           ? fci::ControllerMode::kExternal
                           : fci::ControllerMode::kJointImpedance;
  }
  state.errors = errors_;
  state.reflex_reason = reflex_reason_;
  state.robot_mode = mode_;
  state.control_command_success_rate =
      static_cast<double>(std::count(success_.begin(), success_.end(), true)) /
      static_cast<double>(success_.size());
  fci::putRobotState(outgoing_, state);
  (void)::sendto(udp_, outgoing_.data(), outgoing_.size(), 0,
                 reinterpret_cast<const sockaddr*>(&client_udp_), sizeof client_udp_);
  last_sent_id_ = time_ms_;
  last_send_s_ = hardware::monotonicSeconds();
}

}  // namespace comply::franka
