#pragma once
// The seam between comply's Franka backend (franka_arm.hpp) and a client of the robot's FCI:
// libfranka where it is installed (franka_libfranka_session.hpp), or comply's own client of the
// protocol (fci_session.hpp), or a test's double. What the arm needs from one: the robot's
// state once per robot cycle, torques back, and the few commands around a torque control.
//
// Threads: every call comes from the control thread. read() and writeTorque() are the cycle's
// (real-time: no allocation, no lock another thread holds, no throw); the others run between
// cycles in which the robot holds the arm itself (set-up, a reset's recovery, a change of
// collision thresholds, a deactivation) and may block for a few robot cycles.

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "comply/franka/fci_protocol.hpp"

namespace comply::franka {

/// One state of the robot, as the arm reads it.
struct FrankaSample {
  std::uint64_t time_ms = 0;      ///< the robot's clock: one per state [ms]
  double arrived_s = 0.0;         ///< hardware::monotonicSeconds() when it was received
  std::array<double, 7> q{};      ///< [rad]
  std::array<double, 7> dq{};     ///< [rad/s]
  std::array<double, 7> tau_J{};  ///< the joints' torque sensors [N m]
  /// The robot's estimate of the external wrench at its stiffness frame, base frame, force
  /// first [N, N m], in the robot's sign: what the arm exerts on its surroundings.
  std::array<double, 6> O_F_ext_hat_K{};  // NOLINT(readability-identifier-naming)
  fci::RobotMode robot_mode = fci::RobotMode::kOther;
  /// The robot runs this client's torque control now (external controller, in motion).
  bool torque_control = false;
  std::array<bool, fci::kErrorCount> errors{};              ///< active now
  std::array<bool, fci::kErrorCount> last_motion_errors{};  ///< what ended the last motion
  double command_success_rate = 0.0;  ///< of the last 100 states, answered in time [0, 1]
};

class FrankaSession {
 public:
  virtual ~FrankaSession() = default;

  /// Blocks until the robot's next state (at most `timeout_s`); false when none came or the link
  /// is lost (failure() says why).
  virtual bool read(FrankaSample& sample, double timeout_s) noexcept = 0;
  /// The torque [N m] answering the state read last, on top of the robot's own gravity
  /// compensation. False when it could not go out (failure() says why) or no torque control runs.
  virtual bool writeTorque(std::span<const double, 7> torque_n_m) noexcept = 0;
  /// Why the link failed (a static or a session-owned text, valid until the next call), nullptr
  /// while it works.
  [[nodiscard]] virtual const char* failure() const noexcept = 0;

  /// Starts the client's torque control (the robot's external controller) and gives the state it
  /// started on, the one the first torque answers. "" or why not.
  virtual std::string startTorqueControl(FrankaSample& first) = 0;
  /// Ends it as the client finishes a motion: the robot holds the arm where it is.
  virtual std::string stopTorqueControl() = 0;
  /// The robot's automatic error recovery (a reflex, a limit): "" once it is ready again.
  virtual std::string recover() = 0;
  /// The reflexes' thresholds (the robot takes them only while no motion runs).
  virtual std::string setCollisionThresholds(const fci::CollisionThresholds& thresholds) = 0;
  /// For the start-up line: the client and the robot's protocol version.
  [[nodiscard]] virtual std::string description() const = 0;
};

}  // namespace comply::franka
