#pragma once
// An emulated UR controller on free ports and a UR backend connected to it, for the tests.

#include <chrono>
#include <functional>
#include <memory>
#include <thread>

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

/// Polls `condition` every 10 ms for up to `timeout_s`; its last value.
inline bool eventually(const std::function<bool()>& condition, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace comply::ur::test
