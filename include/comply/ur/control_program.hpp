#pragma once
// The URScript program comply's UR backend sends a UR controller (primary interface), and its
// reading back (the UR controller emulator runs only this program). The program is the arm's side
// of one control cycle: every controller cycle (2 ms) it reads the registers comply writes over
// RTDE and commands the joints with them, in one of three ways fixed when it is sent:
//
//   servoj          position drives follow q          (output.mode position)
//   speedj          velocity drives follow dq         (output.mode velocity)
//   direct_torque  the joint torques, the controller adding gravity and friction
//                   compensation (output.mode torque; PolyScope 5.23 / 10.10 and later)
//
// Registers, from `register_offset` (24 by default: the first of the upper half, which
// PolyScope leaves to external RTDE clients, clear of a fieldbus's lower half):
//   input_int_register_<o>          the controller cycle comply answers (its sample counter)
//   input_int_register_<o+1>        1: drive with the six doubles; 0: stop and stand still
//   input_double_register_<o..o+5>  q [rad], dq [rad/s] or torque [N m], joint by joint
//   output_int_register_<o>         the cycle whose answer the program applied last
//   output_int_register_<o+1>       its instance number while it runs, the negative once its
//                                   watchdog stopped it (so an earlier program's is not taken
//                                   for it)
// Watchdog: once comply has written, a cycle counter that has not moved for `watchdog_s` stops
// the arm (stopj) and ends the program, so the arm stands still when comply stops talking.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "comply/core/actuator_command.hpp"

namespace comply::ur {

/// Refused program text, naming what is missing or wrong.
class ControlProgramError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ControlProgram {
  /// position (servoj), velocity (speedj) or torque (direct_torque).
  OutputMode mode = OutputMode::kPosition;
  double period_s = 0.002;  ///< the controller's cycle [s]
  int register_offset = 24;
  double watchdog_s = 0.05;  ///< [s] without a new cycle's answer before the program stops
  /// servoj: how far ahead the trajectory is smoothed [s] (UR: 0.03 to 0.2) and its
  /// proportional gain (UR: 100 to 2000).
  double servoj_lookahead_s = 0.03;
  double servoj_gain = 1000.0;
  double speedj_acceleration_rad_per_s2 = 20.0;  ///< speedj's largest joint acceleration
  double stop_deceleration_rad_per_s2 = 10.0;    ///< stopj's, for a hold and the watchdog
  /// Which program this is (1 to 2^31 - 2): the backend numbers the programs it sends.
  std::int32_t instance = 1;
};

/// The URScript text of `program`. Throws ControlProgramError for a mode the program has no
/// command for (joint_pd) or values out of the ranges above.
std::string controlProgramScript(const ControlProgram& program);

/// A program text read back: the values controlProgramScript() wrote. Throws ControlProgramError
/// when the text is not comply's control program or a value is missing.
ControlProgram readControlProgram(std::string_view script);

/// The URScript function a mode's program calls each cycle: "servoj", "speedj", "direct_torque".
std::string_view driveCommand(OutputMode mode);

}  // namespace comply::ur
