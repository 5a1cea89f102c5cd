#pragma once
// The emulated UR controller's inside (ur_emulator.hpp): one mutex over the plant, the program
// and the safety state, taken by the controller's cycle, the ports and the tests' calls.

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/ur/rtde_server.hpp"
#include "comply/ur_emulator/ur_emulator.hpp"
#include "text_port.hpp"

namespace comply::ur {

/// The names of the registers a program uses (control_program.hpp), made once per program.
struct ProgramRegisters {
  explicit ProgramRegisters(int offset = 24);
  std::string answer;                 // input_int_register_<o>
  std::string drive;                  // input_int_register_<o+1>
  std::array<std::string, 6> target;  // input_double_register_<o..o+5>
  std::string applied;                // output_int_register_<o>
  std::string flag;                   // output_int_register_<o+1>
};

class UrEmulator::Impl {
 public:
  explicit Impl(const UrEmulatorOptions& options);
  ~Impl();

  // The tests' and the ports' calls (each takes the mutex).
  void protectiveStop();
  void dropPackages(int cycles);
  void closeConnections() { rtde_.closeConnections(); }
  void runScript(const std::string& script);
  std::string dashboard(const std::string& command);
  UrEmulatorStats stats() const;
  UrEmulatorState state() const;
  void withPlant(const std::function<void(sim::SimulatedRobot&)>& edit);

  [[nodiscard]] std::uint16_t rtdePort() const noexcept { return rtde_.port(); }
  [[nodiscard]] std::uint16_t scriptPort() const noexcept { return script_port_->port(); }
  [[nodiscard]] std::uint16_t dashboardPort() const noexcept { return dashboard_port_->port(); }

 private:
  // controller_cycle.cpp: one controller cycle and its parts, with the mutex held.
  void runCycles(const std::stop_token& stop);
  /// Without the mutex: waits until the running program's answer to the last package is in, or
  /// one period after that package was sent.
  void awaitAnswer();
  void cycle();
  void startPendingProgram();
  void applyProgram();
  void command(int drive, const std::array<double, 6>& values);
  void stopProgram(std::int32_t flag);
  void checkSafety();
  void sendOutputs();
  [[nodiscard]] std::int32_t intRegister(const std::string& name) const;
  [[nodiscard]] double doubleRegister(const std::string& name) const;
  void buildPlant(OutputMode actuation);
  void protectiveStopLocked();

  UrEmulatorOptions options_;
  model::RobotDescription robot_;
  mutable std::mutex mutex_;
  std::unique_ptr<sim::SimulatedRobot> plant_;
  OutputMode plant_mode_ = OutputMode::kPosition;
  std::vector<int> dof_address_;  // the arm's joints' MuJoCo dofs (gravity for direct_torque)
  Vector6d wrench_tare_ = Vector6d::Zero();  // the tool's weight at home: the payload's share
  JointState measured_;

  std::uint64_t cycle_ = 0;  // this cycle's index k: its time k * period
  std::int32_t safety_mode_ = 1;
  double stopped_at_s_ = 0.0;  // the protective stop's controller time
  int drop_ = 0;
  double last_send_s_ = 0.0;  // monotonic time the last package was sent

  // The program (control_program.hpp) and its state, as the script's variables.
  std::optional<ControlProgram> pending_;
  ControlProgram program_;
  ProgramRegisters names_;
  bool running_ = false;
  std::int32_t program_flag_ = 0;  // output_int_register_<o+1>
  std::int32_t applied_ = 0;       // output_int_register_<o>
  std::int32_t last_answer_ = 0;
  bool armed_ = false;
  double quiet_s_ = 0.0;
  std::array<double, 6> last_target_{};  // servoj: the last cycle's target
  bool servo_following_ = false;         // servoj: last_target_ is the last cycle's

  std::map<std::string, RtdeValue> registers_;  // kept across connections, as a controller does
  std::vector<bool> sent_;                      // by package index k + 1: sent (not dropped)
  UrEmulatorStats stats_;

  RtdeServer rtde_;
  std::unique_ptr<TextPort> script_port_;
  std::unique_ptr<TextPort> dashboard_port_;
  std::jthread cycle_thread_;
};

}  // namespace comply::ur
