#pragma once
// A UR e-series controller, emulated on comply's MuJoCo UR5e, for testing the UR backend (and
// any RTDE client) without a robot. What it serves, as a controller does, on three TCP ports:
//
//   RTDE (30004)       every output recipe at up to 500 Hz, the input registers
//   secondary (30002)  takes a URScript program; it runs comply's control program only
//                      (control_program.hpp), whose semantics it applies natively each cycle
//   dashboard (29999)  "unlock protective stop", "safetymode", "robotmode", "programState",
//                      "running", "stop", "PolyscopeVersion", "close safety popup", "quit"
//
// Each 2 ms controller cycle: the registers comply wrote are applied as the program would
// (servoj to position servos, speedj to velocity servos, direct_torque on top of the plant's
// own gravity and Coriolis torque; stopj as a brake; the watchdog), the plant steps, a contact
// force above the safety limit makes a protective stop, and the variables go out. Protective
// stops, dropped data packages and closed connections on request, for the tests.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "comply/core/commands.hpp"
#include "comply/sim/scene_xml.hpp"
#include "comply/ur/control_program.hpp"
#include "comply/ur/rtde_packages.hpp"

namespace comply::sim {
class SimulatedRobot;
}

namespace comply::ur {

struct UrEmulatorOptions {
  std::string address = "127.0.0.1";
  std::uint16_t rtde_port = 30004;  ///< 0: any free port (rtdePort() tells); so the others
  std::uint16_t script_port = 30002;
  std::uint16_t dashboard_port = 29999;
  ControllerVersion version{5, 23, 0, 0};
  std::string robot = "ur5e";  ///< a robot description (model::loadRobotDescription)
  sim::SceneOptions scene;     ///< a table to press on, a tool
  double period_s = 0.002;     ///< the controller's cycle [s]
  /// The safety limit on the TCP's contact force [N]: above it, a protective stop. 0: none.
  double protective_stop_force_n = 150.0;
  /// How long a protective stop must last before the dashboard unlocks it [s] (PolyScope: 5).
  double unlock_delay_s = 5.0;
  double servo_bandwidth_hz = 20.0;  ///< the joints' position and velocity servos [Hz]
  /// How long a cycle waits for the answer to the last package [s]: at most one period, as a
  /// controller's cycle does (0, the default). Longer makes a run independent of how this host
  /// schedules the emulator and its client (the tests): an answer after one period still counts
  /// as late, but is applied.
  double answer_wait_s = 0.0;
  /// SCHED_FIFO priority of the cycle and RTDE threads, as a controller's are real-time (0:
  /// normal). Where the process may not have it, they run at normal priority.
  int priority = 0;
};

struct UrEmulatorStats {
  std::uint64_t cycles = 0;    ///< controller cycles run
  std::uint64_t dropped = 0;   ///< data packages not sent, on request
  std::uint64_t answered = 0;  ///< cycles in which the program found a new answer
  /// Answers that came more than one period after their package went out (their cycle applied
  /// an older answer again, unless answer_wait_s waited for them), while the program ran armed.
  std::uint64_t late = 0;
  /// Data packages sent while the program ran whose answer it never applied: none came, or a
  /// newer one had overtaken it by the next cycle.
  std::uint64_t missed = 0;
  std::uint64_t programs = 0;  ///< programs started
  std::uint64_t watchdog_stops = 0;
  std::uint64_t protective_stops = 0;
  std::string last_program_error;  ///< why the last program refused to run ("" if none)
};

/// What the emulated controller shows now.
struct UrEmulatorState {
  std::int32_t safety_mode = 1;
  bool program_running = false;
  OutputMode program_mode = OutputMode::kPosition;
  JointVector position;
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();  ///< base frame
  Vector6d contact_wrench = Vector6d::Zero();  ///< on the tool, base frame, about the TCP
  double time_s = 0.0;                         ///< the controller's time
};

class UrEmulator {
 public:
  /// Builds the plant at the robot's home pose, listens on the three ports, starts the
  /// controller's cycle. Throws (sim::SimError, RtdeError, std::runtime_error) naming what failed.
  explicit UrEmulator(const UrEmulatorOptions& options);
  ~UrEmulator();
  UrEmulator(const UrEmulator&) = delete;
  UrEmulator& operator=(const UrEmulator&) = delete;

  [[nodiscard]] std::uint16_t rtdePort() const noexcept;
  [[nodiscard]] std::uint16_t scriptPort() const noexcept;
  [[nodiscard]] std::uint16_t dashboardPort() const noexcept;

  /// As if a safety limit tripped: the arm stops, the program ends, safety mode PROTECTIVE_STOP.
  void protectiveStop();
  /// The next `cycles` controller cycles send no data package.
  void dropPackages(int cycles);
  /// Every RTDE connection closed (a cable pulled); clients may connect again.
  void closeConnections();
  /// A URScript program, as the secondary interface takes one (for the tests; the port calls it).
  void runScript(const std::string& script);
  /// The dashboard's answer to one command line.
  std::string dashboard(const std::string& command);

  [[nodiscard]] UrEmulatorStats stats() const;
  [[nodiscard]] UrEmulatorState state() const;
  /// Runs `edit` on the plant between two cycles (a push: setExternalWrench).
  void withPlant(const std::function<void(sim::SimulatedRobot&)>& edit);

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace comply::ur
