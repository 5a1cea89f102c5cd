#pragma once
// A loop observer that stalls the loop's thread once: it sleeps 15 ms after the cycle numbered
// `stall_after`, as a host preempted for that long would, and keeps every cycle's lateness and
// whether it overran. For the tests of lateness and overruns on the wall clock.

#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "comply/hardware/control_loop.hpp"

namespace comply::testing {

class StallingObserver final : public hardware::LoopObserver {
 public:
  static constexpr std::chrono::milliseconds kStall{15};

  explicit StallingObserver(std::uint64_t stall_after) : stall_after_(stall_after) {}
  void afterCycle(const hardware::CycleRecord& record) override {
    lateness_s.push_back(record.start_lateness_s);
    overrun.push_back(record.overrun);
    if (record.index == stall_after_) {
      std::this_thread::sleep_for(kStall);
    }
  }
  std::vector<double> lateness_s;
  std::vector<bool> overrun;

 private:
  std::uint64_t stall_after_;
};

}  // namespace comply::testing
