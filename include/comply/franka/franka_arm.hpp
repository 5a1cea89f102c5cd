#pragma once
// A Franka arm (FR3, Panda) as comply's hardware, without ROS: torque control at the robot's
// 1 kHz through an FCI client (franka_session.hpp), the robot's clock pacing the loop.
//
//   FrankaArm arm(makeFciSession({.robot_ip = "172.16.0.2"}), {});
//   FrankaClock clock(arm);  // one cycle per robot state
//   ControlLoop loop(arm, controller, clock, {.period_s = 0.001});
//
// The robot adds gravity to the torque it is sent (compensatesGravity), measures joint torques
// (the state's effort) and estimates the external wrench (readWrench), numbers its states
// (readSequence). Its errors and modes are robotStop() texts (franka_errors.hpp): the cycle
// enters FAULT naming them. recover() runs the robot's error recovery for a reset. hold() ends
// the torque control: the robot then holds the arm itself, until a cycle writes a torque without
// asking for the hold again (the control starts at the next sample).
//
// Threads: the control thread makes every call to the session. What another thread asks for
// (recover(), new collision thresholds) the control thread carries out at its next sample, when
// no torque control runs or it ends it for that: those cycles block for a few robot cycles.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "comply/franka/franka_session.hpp"
#include "comply/hardware/hardware_interface.hpp"
#include "comply/hardware/loop_clock.hpp"

namespace comply::franka {

struct FrankaArmOptions {
  /// The reflexes' thresholds the arm starts with (frankaCollisionThresholds()).
  fci::CollisionThresholds collision;
  /// No state for this long [s]: the link is lost (a robotStop()).
  double link_timeout_s = 0.1;
  /// The robot's collision thresholds stay this far above the contact comply's own reflex lets
  /// through (allowContact), so that comply's reflex acts first [-].
  double contact_margin = 1.5;
  /// The lever [m] from a contact force at the TCP to the joint torque it makes, for the joint
  /// thresholds (about the FR3's reach).
  double contact_lever_m = 1.0;
  /// How long recover() waits for the robot [s].
  double recovery_timeout_s = 5.0;
};

/// Thresholds from one joint torque [N m] and one force [N], and a torque about the flange
/// [N m] (negative: the force times 0.1 m), as libfranka's examples set them: contact at 80 % of
/// collision.
fci::CollisionThresholds frankaCollisionThresholds(double collision_torque_n_m,
                                                   double collision_force_n,
                                                   double collision_flange_torque_n_m = -1.0);

struct FrankaArmStats {
  std::uint64_t states = 0;  ///< robot states read
  /// Robot states between two reads under comply's torque control that the loop never saw
  std::uint64_t skipped = 0;
  std::uint64_t controls = 0;    ///< torque controls started
  std::uint64_t stops = 0;       ///< robot stops seen (errors, user stop, lost link)
  std::uint64_t recoveries = 0;  ///< error recoveries run
  std::uint64_t threshold_changes = 0;
  double worst_success_rate = 1.0;  ///< the robot's command success rate, lowest seen
};

class FrankaArm final : public hardware::HardwareInterface {
 public:
  /// Sets the collision thresholds, reads a first state. Throws hardware::BackendError naming
  /// what failed.
  FrankaArm(std::unique_ptr<FrankaSession> session, FrankaArmOptions options);
  ~FrankaArm() override;
  FrankaArm(const FrankaArm&) = delete;
  FrankaArm& operator=(const FrankaArm&) = delete;

  [[nodiscard]] int dof() const noexcept override { return 7; }
  bool read(JointState& state) noexcept override;
  /// The robot's external wrench estimate, turned to what the wrist sensor of comply's
  /// convention reads: the wrench on the tool [N, N m], base frame, about the stiffness frame.
  bool readWrench(Vector6d& wrench) noexcept override;
  bool readSequence(std::uint64_t& sequence) noexcept override;
  [[nodiscard]] const char* robotStop() noexcept override { return stop_; }
  /// Sends `torque` through the running torque control. Without one, the robot holds the arm
  /// this cycle and the control starts at the next sample (blocking a few robot cycles), unless
  /// hold() follows in the same cycle.
  bool write(std::span<const double> torque) noexcept override;
  /// Ends the torque control: the robot holds the arm itself.
  bool hold() noexcept override;
  [[nodiscard]] bool compensatesGravity() const noexcept override { return true; }
  [[nodiscard]] std::string recover() override;
  /// Keeps the collision thresholds contact_margin above the contact comply lets through
  /// (never below the ones the arm started with or was last asked for); a change of more than
  /// 10 % is taken at the next sample, the torque control ending and starting for it.
  void allowContact(double force_n, double torque_n_m) noexcept override;
  [[nodiscard]] std::string summary() const override;

  /// Any thread: new collision thresholds, taken at the control thread's next sample (a torque
  /// control running ends for it and starts again). False while an earlier change waits or
  /// another thread's is being made.
  bool requestCollisionThresholds(const fci::CollisionThresholds& thresholds) noexcept;

  /// The control thread's clock: blocks until the robot's next state (at most link_timeout_s)
  /// and keeps it for read(); first carries out what other threads asked for.
  bool awaitSample() noexcept;
  /// The newest state's time on the robot's clock [s]. Control thread.
  [[nodiscard]] double sampleTime() const noexcept;
  [[nodiscard]] double sampleArrival() const noexcept { return sample_.arrived_s; }
  /// The last awaitSample() brought a new state. Control thread.
  [[nodiscard]] bool sampleFresh() const noexcept { return fresh_; }
  [[nodiscard]] FrankaArmStats stats() const noexcept;
  [[nodiscard]] const FrankaSession& session() const noexcept { return *session_; }

 private:
  void carryOutRequests() noexcept;
  /// Sets `thresholds`, ending a running torque control for it and starting it again.
  void applyThresholds(const fci::CollisionThresholds& thresholds) noexcept;
  [[nodiscard]] fci::CollisionThresholds allowedThresholds() const;
  void startControl() noexcept;
  void noteStop(const char* stop) noexcept;

  std::unique_ptr<FrankaSession> session_;
  FrankaArmOptions options_;
  FrankaSample sample_;         // control thread: the newest state
  bool sample_valid_ = false;   // control thread
  bool fresh_ = false;          // control thread: sample_ came with the last awaitSample()
  bool controlling_ = false;    // control thread: a torque control runs
  bool wants_control_ = false;  // control thread: a write() without a hold() after it
  FrankaSample started_on_;     // control thread: the state the last torque control started on
  bool started_ = false;        // control thread: started_on_ is the next cycle's sample
  const char* stop_ = nullptr;  // control thread
  std::atomic<bool> stopped_{false};  // stop_ != nullptr, for recover()
  std::atomic<int> recovery_{0};      // 0 none, 1 asked, 2 done, 3 failed
  std::string recovery_error_;        // written by the control thread before recovery_ = 3
  /// requestCollisionThresholds(): 0 none, 1 being written (one requester), 2 waiting for the
  /// control thread.
  std::atomic<int> thresholds_request_{0};
  fci::CollisionThresholds thresholds_;  // written while thresholds_request_ is 1
  fci::CollisionThresholds base_;        // control thread: the thresholds last asked for
  double allowed_force_n_ = 0.0;         // control thread: the contact the robot's are set for
  double allowed_torque_n_m_ = 0.0;
  bool contact_pending_ = false;  // control thread: thresholds for a new allowance to set
  std::atomic<std::uint64_t> states_{0};
  std::atomic<std::uint64_t> skipped_{0};
  std::atomic<std::uint64_t> controls_{0};
  std::atomic<std::uint64_t> stops_{0};
  std::atomic<std::uint64_t> recoveries_{0};
  std::atomic<std::uint64_t> threshold_changes_{0};
  std::atomic<double> worst_success_rate_{1.0};
};

/// The loop's clock: one cycle per robot state.
class FrankaClock final : public hardware::LoopClock {
 public:
  explicit FrankaClock(FrankaArm& arm) : arm_(arm) {}
  [[nodiscard]] double now() noexcept override { return arm_.sampleTime(); }
  void waitUntil(double time_s) noexcept override;
  [[nodiscard]] double lateness(double time_s) noexcept override;

 private:
  FrankaArm& arm_;
};

}  // namespace comply::franka
