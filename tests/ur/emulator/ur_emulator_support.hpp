#pragma once
// An emulated UR controller on free ports and a UR backend connected to it, for the tests.

#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "../../support/eventually.hpp"
#include "comply/ur/ur_arm.hpp"
#include "comply/ur_emulator/ur_emulator.hpp"

namespace comply::ur::test {

inline UrEmulatorOptions freePorts(UrEmulatorOptions options = {}) {
  options.rtde_port = 0;
  options.script_port = 0;
  options.dashboard_port = 0;
  options.unlock_delay_s = 0.2;
  return options;
}

inline UrArmOptions armFor(const UrEmulator& emulator, OutputMode mode) {
  UrArmOptions options;
  options.robot_ip = "127.0.0.1";
  options.rtde_port = emulator.rtdePort();
  options.script_port = emulator.scriptPort();
  options.program.mode = mode;
  options.reconnect_interval_s = 0.1;
  return options;
}

using comply::testing::eventually;

}  // namespace comply::ur::test
