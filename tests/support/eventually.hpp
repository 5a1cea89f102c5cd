#pragma once
// Waiting in a test for what another thread (a control loop, an emulator) brings about.

#include <chrono>
#include <functional>
#include <thread>

namespace comply::testing {

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

}  // namespace comply::testing
