#pragma once
// The emulated Franka robot and comply's FCI client on loopback, for the tests.

#include <memory>
#include <string>

#include "comply/franka/fci_session.hpp"
#include "comply/franka_emulator/franka_emulator.hpp"

namespace comply::franka::testing {

inline FrankaEmulatorOptions emulatorOptions(double answer_wait_s) {
  FrankaEmulatorOptions options;
  options.command_port = 0;  // any free port
  options.answer_wait_s = answer_wait_s;
  return options;
}

inline std::unique_ptr<FrankaSession> connect(const FrankaEmulator& robot) {
  FciSessionOptions options;
  options.robot_ip = "127.0.0.1";
  options.command_port = robot.commandPort();
  return makeFciSession(options);
}

/// Starts the torque control; "" or why not.
inline std::string start(FrankaSession& session) {
  FrankaSample first;
  return session.startTorqueControl(first);
}

}  // namespace comply::franka::testing
