#pragma once
// A UR e-series arm as comply's hardware, without ROS: state over RTDE at the controller's rate
// (500 Hz: joint positions and velocities, joint torques where the controller reports them, the
// wrist's force/torque sensor, the robot and safety modes, the controller's cycle as the sample
// counter), commands through comply's control program (control_program.hpp), which the backend
// sends the controller itself and feeds through RTDE's input registers.
//
//   UrArm arm({.robot_ip = "192.168.1.10", .program = {.mode = OutputMode::kPosition}});
//   UrClock clock(arm);  // the loop runs on the controller's cycles
//   ControlLoop loop(arm, controller, clock, {.period_s = 0.002});
//
// Threads. A link thread (not real-time) owns the RTDE connection: it receives every data
// package, publishes it (a triple buffer and an eventfd the loop's clock waits on), notices a
// stop (protective, emergency, the program ended, the link lost: robotStop()), reconnects after a
// lost link and sends the program again once the controller can run it. The control thread reads
// the newest sample and writes its answer straight to the socket, a package of fixed size
// encoded in place: no allocation, no lock.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "comply/core/triple_buffer.hpp"
#include "comply/hardware/hardware_interface.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/ur/control_program.hpp"
#include "comply/ur/rtde_packages.hpp"

namespace comply::ur {

class RtdeClient;

struct UrArmOptions {
  std::string robot_ip;               ///< IPv4
  std::uint16_t rtde_port = 30004;    ///< RTDE
  std::uint16_t script_port = 30002;  ///< secondary interface: takes a URScript program
  ControlProgram program;             ///< its mode is the controller's output.mode
  double connect_timeout_s = 5.0;     ///< set-up and the program's start [s]
  /// No data package for this long [s]: the link is lost (a robotStop()).
  double link_timeout_s = 0.05;
  double reconnect_interval_s = 0.5;  ///< between attempts once the link is lost [s]
};

/// The newest data package, as the control thread reads it.
struct UrSample {
  double time_s = 0.0;             ///< the controller's time [s] (RTDE timestamp)
  std::uint64_t cycle = 0;         ///< its controller cycle: time_s / period
  double arrived_s = 0.0;          ///< hardware::monotonicSeconds() when it was received
  std::array<double, 6> q{};       ///< rad
  std::array<double, 6> dq{};      ///< rad/s
  std::array<double, 6> tau{};     ///< N m; NaN where the controller reports no joint torque
  std::array<double, 6> wrench{};  ///< actual_TCP_force: base frame, at the TCP [N, N m]
  const char* stop = nullptr;      ///< stopReason() of this package, or the link's
  /// Stops published so far and the last of them: one that came and went between two reads of
  /// the control thread is still seen once.
  std::uint64_t stops = 0;
  const char* last_stop = nullptr;
};

struct UrLinkStats {
  std::uint64_t packages = 0;        ///< data packages received
  std::uint64_t skipped_cycles = 0;  ///< controller cycles between packages that never came
  /// Packages the control thread never answered: a newer one had come by the time it woke.
  std::uint64_t unanswered = 0;
  std::uint64_t connections = 0;  ///< RTDE connections made (1 + reconnects)
  std::uint64_t programs_sent = 0;
};

class UrArm final : public hardware::HardwareInterface {
 public:
  /// Connects, sets up the recipes, sends the program and waits until it runs. Throws
  /// hardware::BackendError naming what failed (the address, a refused variable, a controller too
  /// old for direct_torque, a stop that keeps the program from running).
  explicit UrArm(UrArmOptions options);
  ~UrArm() override;
  UrArm(const UrArm&) = delete;
  UrArm& operator=(const UrArm&) = delete;

  [[nodiscard]] int dof() const noexcept override { return 6; }
  bool read(JointState& state) noexcept override;
  bool readWrench(Vector6d& wrench) noexcept override;
  bool readSequence(std::uint64_t& sequence) noexcept override;
  /// The control thread's (the sample read() returned): see lastStop() for any other.
  [[nodiscard]] const char* robotStop() noexcept override { return stop_; }
  /// Any thread: the stop the link thread published last (nullptr while the arm runs).
  [[nodiscard]] const char* lastStop() const noexcept {
    return last_stop_.load(std::memory_order_acquire);
  }
  [[nodiscard]] bool accepts(OutputMode mode) const noexcept override {
    return mode == options_.program.mode;
  }
  bool write(std::span<const double> torque) noexcept override;
  bool writeCommand(const ActuatorCommand& command) noexcept override;
  /// The program's stopj: the arm decelerates and stands still until the next command. False
  /// when this cycle already sent its command (one answer per controller cycle).
  bool hold() noexcept override;
  /// direct_torque: the controller adds gravity (and friction) compensation itself.
  [[nodiscard]] bool compensatesGravity() const noexcept override {
    return options_.program.mode == OutputMode::kTorque;
  }

  /// The control thread's clock: blocks until a package newer than the last one it returned for
  /// came, or `timeout_s` passed; false then.
  bool awaitSample(double timeout_s) noexcept;
  /// The newest sample's controller time [s] and its arrival (monotonic) [s].
  [[nodiscard]] double sampleTime() const noexcept;
  [[nodiscard]] double sampleArrival() const noexcept;
  [[nodiscard]] UrLinkStats stats() const noexcept;
  /// "UR link: N packages, ..." (stats()).
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const ControllerVersion& controllerVersion() const noexcept { return version_; }
  [[nodiscard]] const UrArmOptions& options() const noexcept { return options_; }

  class Link;

 private:
  /// Sends the registers: the answer to the sample read last, drive (1) or stop (0).
  bool send(int drive, const JointVector* values) noexcept;

  UrArmOptions options_;
  ControllerVersion version_;
  TripleBuffer<UrSample> sample_;  // written by the link thread, read by the control thread
  std::atomic<const char*> last_stop_{nullptr};
  std::atomic<bool> answer_broken_{false};  // a send went out in part: the stream is out of step
  std::atomic<double> newest_time_s_{0.0};
  std::atomic<double> newest_arrival_s_{0.0};
  std::atomic<std::uint64_t> received_{0};  // packages published
  std::uint64_t awaited_ = 0;               // control thread: packages its clock saw
  std::atomic<std::uint64_t> unanswered_{0};
  int wakeup_ = -1;              // eventfd: one count per package
  std::atomic<int> socket_{-1};  // the RTDE socket the answers go to
  std::atomic<std::uint8_t> input_recipe_{0};
  std::uint64_t answered_cycle_ = 0;  // control thread: the cycle of the sample read last
  bool answered_ = false;             // control thread: an answer to it went out
  const char* stop_ = nullptr;        // control thread: robotStop() for the sample read last
  std::uint64_t stops_seen_ = 0;      // control thread: UrSample::stops at the last read
  std::array<std::uint8_t, 64> package_{};
  std::unique_ptr<Link> link_;
  std::jthread link_thread_;
};

/// A loop clock that runs on the controller's cycles: waitUntil() returns at the next data
/// package (or after the link timeout, so that a lost link is still seen by a cycle); now() is
/// the controller's time; lateness() is how long after its package arrived the cycle starts.
class UrClock final : public hardware::LoopClock {
 public:
  explicit UrClock(UrArm& arm) : arm_(arm) {}
  [[nodiscard]] double now() noexcept override { return arm_.sampleTime(); }
  void waitUntil(double time_s) noexcept override;
  [[nodiscard]] double lateness(double time_s) noexcept override;

 private:
  UrArm& arm_;
};

}  // namespace comply::ur
