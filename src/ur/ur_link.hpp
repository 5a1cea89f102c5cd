#pragma once
// The UR backend's link thread (ur_arm.hpp): the RTDE connection, the program, reconnection.

#include <memory>
#include <stop_token>
#include <vector>

#include "comply/ur/rtde_client.hpp"
#include "comply/ur/ur_arm.hpp"
#include "script_sender.hpp"

namespace comply::ur {

class UrArm::Link {
 public:
  explicit Link(UrArm& arm) : arm_(arm) {}
  /// Connects and sets up the recipes, started; throws hardware::BackendError.
  ControllerVersion connect();
  /// Sends the program and waits until the controller says it runs; throws
  /// hardware::BackendError naming the stop that keeps it from running.
  void startProgram(double timeout_s);
  /// The thread's body: receive, publish, notice stops, reconnect, restart the program.
  void run(const std::stop_token& stop);
  [[nodiscard]] UrLinkStats stats() const noexcept;

 private:
  /// One package (or a timeout, or the link's end); true when one was published.
  bool receiveOnce(double timeout_s);
  void publish();
  void publishStop(const char* why);
  /// Counts a stop that differs from `previous` (UrSample::stops).
  void noteStop(const char* previous);
  void lose(const char* why);
  /// `write_hold`: the registers say "stand still" first (only while the control thread does not
  /// answer yet).
  void sendProgram(bool write_hold);
  /// Reads what the answer connection's controller sent (its slow output recipe); a closed one
  /// ends the link.
  void drainCommands();
  /// A lost link: a new connection, at most every reconnect_interval_s.
  void tryReconnect();
  /// The controller can run the program again (a stop cleared) but it is not running: sent again,
  /// at most once a second.
  void restartProgramIfStopped();

  UrArm& arm_;
  std::unique_ptr<RtdeClient> client_;    // the output recipe: read by this thread
  std::unique_ptr<RtdeClient> commands_;  // the input recipe: written by the control thread
  /// The last link's commanding client, kept open one reconnect longer: the control thread may
  /// still be sending to its socket, whose number must not be reused meanwhile.
  std::unique_ptr<RtdeClient> retired_;
  Recipe outputs_;
  Recipe inputs_;
  bool has_torque_ = false;
  std::vector<RtdeValue> values_;
  UrSample last_;
  std::vector<RtdeValue> scratch_;
  bool program_running_ = false;
  std::int32_t instance_ = 0;      // the program sent last (control_program.hpp)
  bool restart_allowed_ = false;   // a stop comply recovers from came since it was sent
  bool seen_running_ = false;      // it ran since it was sent
  bool controller_ready_ = false;  // normal safety, powered, running
  double last_program_s_ = -1e9;
  double last_attempt_s_ = -1e9;
  double last_package_s_ = 0.0;
  std::atomic<std::uint64_t> packages_{0};
  std::atomic<std::uint64_t> skipped_{0};
  std::atomic<std::uint64_t> connections_{0};
  std::atomic<std::uint64_t> programs_{0};
};

}  // namespace comply::ur
