#pragma once
// Stage "watchdog": no command (and no chunk playing) for command_timeout_s. It only tells when
// the silence began to count; what follows (hold the reference or re-anchor it at the measured
// pose) is the command stage's, which owns the command in force. Real-time.

namespace comply::pipeline {

class CommandWatchdog {
 public:
  /// `timeout_s` <= 0: off.
  explicit CommandWatchdog(double timeout_s) noexcept : timeout_s_(timeout_s) {}

  /// Activation: the silence counts from controller time 0.
  void reset() noexcept { heard(0.0); }
  /// A command was taken, or a chunk played, at controller time `time_s`.
  void heard(double time_s) noexcept {
    last_command_s_ = time_s;
    expired_ = false;
  }
  /// True once, in the first cycle whose time is timeout_s past the last command.
  bool expires(double time_s) noexcept {
    if (expired_ || timeout_s_ <= 0.0 || time_s - last_command_s_ < timeout_s_) {
      return false;
    }
    expired_ = true;
    return true;
  }

 private:
  double timeout_s_ = 0.0;
  double last_command_s_ = 0.0;
  bool expired_ = false;
};

}  // namespace comply::pipeline
