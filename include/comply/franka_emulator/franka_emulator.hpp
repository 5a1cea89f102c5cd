#pragma once
// A Franka robot's FCI (fci_protocol.hpp, protocol version 7), emulated on comply's MuJoCo FR3,
// for testing the Franka backend and any libfranka program without a robot. What it serves, as
// the robot does:
//
//   TCP (1337)  Connect (the version checked), Move (torque control; joint position and velocity
//               motions with the robot's joint impedance), StopMove, SetCollisionBehavior and the
//               other setters (refused while a motion runs), AutomaticErrorRecovery;
//               LoadModelLibrary is answered with an error (no model library is served)
//   UDP         the robot's state every 1 ms to the client's port; its commands back
//
// The robot's rules: a command must answer the state just sent; 20 states in a row without one
// end the motion with communication_constraints_violation. A motion ends with a reflex when the
// external force or a joint's external torque passes its collision threshold (cartesian_reflex,
// joint_reflex); the robot then holds the arm in Reflex until an error recovery. The torques a
// client sends come on top of the robot's gravity compensation (the plant's own gravity, from
// comply's model of the arm). Outside a motion the robot holds the arm where it is.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "comply/core/commands.hpp"
#include "comply/franka/fci_protocol.hpp"
#include "comply/sim/scene_xml.hpp"

namespace comply::sim {
class SimulatedRobot;
}

namespace comply::franka {

struct FrankaEmulatorOptions {
  std::string address = "127.0.0.1";
  std::uint16_t command_port = fci::kCommandPort;  ///< 0: any free port (commandPort() tells)
  std::string robot = "fr3";  ///< a robot description (model::loadRobotDescription), 7 joints
  sim::SceneOptions scene;    ///< a table to press on, a tool
  /// States in a row without a command that end a motion (the robot's rule: 20).
  int lost_in_a_row_limit = 20;
  /// How long a cycle waits for the answer to the state it sent last [s]: not at all (0, the
  /// robot's way: a command not in by the next cycle is lost). Longer makes a run independent of
  /// how this host schedules the emulator and its client (the tests); such an answer counts as
  /// late, but is applied.
  double answer_wait_s = 0.0;
  /// The reflexes' thresholds until a client sets its own [N m, N].
  double collision_torque_n_m = 20.0;
  double collision_force_n = 20.0;
  double recovery_s = 0.05;  ///< how long the automatic error recovery takes [s]
  /// SCHED_FIFO priority of the robot's cycle (0: normal). Where the process may not have it, it
  /// runs at normal priority.
  int priority = 0;
};

struct FrankaEmulatorStats {
  std::uint64_t states = 0;       ///< states sent
  std::uint64_t dropped = 0;      ///< states not sent, on request
  std::uint64_t connections = 0;  ///< clients that connected (and passed the version check)
  std::uint64_t motions = 0;      ///< motions started
  /// States of a motion answered by a command for them, in time or (answer_wait_s) late.
  std::uint64_t answered = 0;
  std::uint64_t late = 0;  ///< of those, in after the next cycle's start
  std::uint64_t lost = 0;  ///< states of a motion no command answered
  std::uint64_t longest_lost_run = 0;
  std::uint64_t reflexes = 0;
  std::uint64_t recoveries = 0;
  std::string last_reflex;  ///< its errors by name ("communication_constraints_violation")
  fci::CollisionThresholds collision;  ///< the thresholds in force
};

/// What the emulated robot shows now.
struct FrankaEmulatorState {
  fci::RobotMode mode = fci::RobotMode::kIdle;
  bool torque_control = false;  ///< a client's torque control runs
  JointVector position;
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();  ///< base frame
  Vector6d contact_wrench = Vector6d::Zero();  ///< on the tool, base frame, about the TCP
  std::uint64_t time_ms = 0;
};

class FrankaEmulator {
 public:
  /// Builds the plant at the robot's home pose, listens on the command port, starts the robot's
  /// cycle. Throws (sim::SimError, model::ModelError, std::runtime_error) naming what failed.
  explicit FrankaEmulator(const FrankaEmulatorOptions& options);
  ~FrankaEmulator();
  FrankaEmulator(const FrankaEmulator&) = delete;
  FrankaEmulator& operator=(const FrankaEmulator&) = delete;

  [[nodiscard]] std::uint16_t commandPort() const noexcept;

  /// As if the robot's own check tripped: a running motion ends with a reflex naming
  /// errorName(error_index) (franka_errors.hpp); in Idle the robot goes to Reflex too.
  void reflex(int error_index);
  /// The next `count` commands from the client are lost on the way.
  void loseCommands(int count);
  /// The next `count` states are not sent.
  void dropStates(int count);
  /// A wrench on the tool at the TCP, base frame, force first [N, N m] (a push); zero removes it.
  void push(const Vector6d& wrench);
  /// The command connection closed (a cable pulled); a client may connect again.
  void closeConnection();

  [[nodiscard]] FrankaEmulatorStats stats() const;
  [[nodiscard]] FrankaEmulatorState state() const;
  /// Runs `edit` on the plant between two cycles.
  void withPlant(const std::function<void(sim::SimulatedRobot&)>& edit);

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace comply::franka
