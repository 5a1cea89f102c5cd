// A FrankaSession through the user's libfranka (franka_backend.hpp): its external control loop
// (startTorqueControl, then readOnce and writeOnce per state), so that comply's loop keeps the
// clock. Built only when CMake found libfranka (0.13 and later have this interface).

#include <franka/active_control_base.h>
#include <franka/exception.h>
#include <franka/robot.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <thread>

#include "comply/franka/franka_errors.hpp"
#include "comply/hardware/backend.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "franka_backend.hpp"

namespace comply::host {
namespace {

constexpr const char* kAbandoned =
    "the link to the Franka robot was lost: start comply run again to connect";

/// libfranka's error flags by name ("["joint_reflex", ...]") into the wire's order.
std::array<bool, franka::fci::kErrorCount> flagsOf(const ::franka::Errors& errors) {
  std::array<bool, franka::fci::kErrorCount> flags{};
  if (!static_cast<bool>(errors)) {
    return flags;
  }
  const auto text = static_cast<std::string>(errors);
  for (int index = 0; index < franka::fci::kErrorCount; ++index) {
    const std::string quoted = std::string("\"") + franka::errorName(index) + "\"";
    flags[static_cast<std::size_t>(index)] = text.find(quoted) != std::string::npos;
  }
  return flags;
}

class LibfrankaSession final : public franka::FrankaSession {
 public:
  LibfrankaSession(const std::string& robot_ip, bool realtime) try
      : robot_(std::make_unique<::franka::Robot>(
            robot_ip,
            realtime ? ::franka::RealtimeConfig::kEnforce : ::franka::RealtimeConfig::kIgnore)) {
    version_ = robot_->serverVersion();
  } catch (const ::franka::Exception& error) {
    throw hardware::BackendError("libfranka could not connect to the Franka robot at " + robot_ip +
                                 ": " + error.what());
  }

  ~LibfrankaSession() override {
    try {
      (void)stopTorqueControl();
    } catch (...) {
    }
  }

  bool read(franka::FrankaSample& sample, double timeout_s) noexcept override {
    if (!robot_) {
      // Abandoned: no state comes; wait as a read would (libfranka's own timeout applies to a
      // working link).
      std::this_thread::sleep_for(std::chrono::duration<double>(timeout_s));
      failure_ = failure_text_.data();
      return false;
    }
    try {
      ::franka::RobotState state;
      if (control_) {
        try {
          state = control_->readOnce().first;
        } catch (const ::franka::ControlException& error) {
          // The robot ended the motion (a reflex, a limit): its state names why.
          noteFailure(error.what());
          endControl();
          state = robot_->readOnce();
        }
      } else {
        state = robot_->readOnce();
      }
      toSample(state, sample);
      failure_ = nullptr;
      return true;
    } catch (const std::exception& error) {
      noteFailure(error.what());
      failure_ = failure_text_.data();
      abandon();
      return false;
    }
  }

  bool writeTorque(std::span<const double, 7> torque_n_m) noexcept override {
    if (!control_) {
      return false;
    }
    try {
      std::array<double, 7> torque{};
      std::copy(torque_n_m.begin(), torque_n_m.end(), torque.begin());
      control_->writeOnce(::franka::Torques(torque));
      return true;
    } catch (const std::exception& error) {
      noteFailure(error.what());
      failure_ = failure_text_.data();
      return false;
    }
  }

  [[nodiscard]] const char* failure() const noexcept override { return failure_; }

  std::string startTorqueControl(franka::FrankaSample& first) override {
    if (!robot_) {
      return kAbandoned;
    }
    try {
      if (!control_) {
        control_ = robot_->startTorqueControl();
      }
      toSample(control_->readOnce().first, first);
      return {};
    } catch (const ::franka::Exception& error) {
      endControl();
      return error.what();
    }
  }

  std::string stopTorqueControl() override {
    if (!control_) {
      return {};
    }
    try {
      control_->writeOnce(::franka::MotionFinished(::franka::Torques({0, 0, 0, 0, 0, 0, 0})));
      control_.reset();
      return {};
    } catch (const ::franka::Exception& error) {
      endControl();
      return error.what();
    }
  }

  std::string recover() override {
    if (!robot_) {
      return kAbandoned;
    }
    endControl();
    try {
      robot_->automaticErrorRecovery();
      return {};
    } catch (const ::franka::Exception& error) {
      return error.what();
    }
  }

  std::string setCollisionThresholds(const franka::fci::CollisionThresholds& t) override {
    if (!robot_) {
      return kAbandoned;
    }
    try {
      robot_->setCollisionBehavior(t.torque_contact_acceleration, t.torque_collision_acceleration,
                                   t.torque_contact_nominal, t.torque_collision_nominal,
                                   t.force_contact_acceleration, t.force_collision_acceleration,
                                   t.force_contact_nominal, t.force_collision_nominal);
      return {};
    } catch (const ::franka::Exception& error) {
      return error.what();
    }
  }

  [[nodiscard]] std::string description() const override {
    return "libfranka, robot protocol version " + std::to_string(version_);
  }

 private:
  void toSample(const ::franka::RobotState& state, franka::FrankaSample& sample) const {
    sample.time_ms = state.time.toMSec();
    sample.arrived_s = hardware::monotonicSeconds();
    sample.q = state.q;
    sample.dq = state.dq;
    sample.tau_J = state.tau_J;
    sample.O_F_ext_hat_K = state.O_F_ext_hat_K;
    sample.robot_mode = static_cast<franka::fci::RobotMode>(static_cast<int>(state.robot_mode));
    sample.torque_control = control_ != nullptr && state.robot_mode == ::franka::RobotMode::kMove;
    sample.errors = flagsOf(state.current_errors);
    sample.last_motion_errors = flagsOf(state.last_motion_errors);
    sample.command_success_rate = state.control_command_success_rate;
  }

  void endControl() noexcept {
    try {
      control_.reset();  // a control the robot ended: libfranka cancels what is left of it
    } catch (...) {
    }
  }

  /// The connection is gone. libfranka's control object would cancel its motion over it when
  /// destroyed, and that throws from a destructor (the process ends): it and the robot object
  /// it locks are left undestroyed instead. Every later call fails; comply run must start again.
  void abandon() noexcept {
    (void)control_.release();  // NOLINT(bugprone-unused-return-value): deliberately leaked
    (void)robot_.release();    // NOLINT(bugprone-unused-return-value)
  }

  void noteFailure(const char* what) noexcept {
    std::strncpy(failure_text_.data(), what, failure_text_.size() - 1);
  }

  std::unique_ptr<::franka::Robot> robot_;  // nullptr once abandoned
  std::unique_ptr<::franka::ActiveControlBase> control_;
  std::uint16_t version_ = 0;
  std::array<char, 512> failure_text_{};
  const char* failure_ = nullptr;
};

}  // namespace

bool libfrankaBuiltIn() noexcept {
  return true;
}

std::unique_ptr<franka::FrankaSession> makeLibfrankaSession(const std::string& robot_ip,
                                                            bool realtime) {
  return std::make_unique<LibfrankaSession>(robot_ip, realtime);
}

}  // namespace comply::host
