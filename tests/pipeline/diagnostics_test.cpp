// The fault and rejection texts of the diagnostics, written by two threads (the cycle and the
// intake), never tear and never block a reader.

#include "comply/pipeline/diagnostics.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

namespace comply::pipeline {
namespace {

TEST(Diagnostics, FaultAndRejectionWritersNeverBlockAReader) {
  // Two writers on one text used to leave its sequence counter odd and a reader spinning.
  constexpr auto kWriterPause = std::chrono::microseconds(20);  // 50 kHz, above any real rate
  Diagnostics diagnostics;
  std::atomic<bool> stop{false};
  std::atomic<int> fault_writes{0};
  std::atomic<int> rejection_writes{0};
  // Writers pause between texts, as real ones do (at most one text per cycle or command): a
  // writer that rewrites its slot back to back can starve a seqlock reader on a 2-core machine.
  // Each writer writes at least once: on a busy machine the reader's loop can end before a
  // writer thread is first scheduled, and the final check needs both texts.
  const auto writer = [&](auto write, std::atomic<int>& writes) {
    return std::thread([&, write] {
      do {
        write();
        writes.fetch_add(1);
        std::this_thread::sleep_for(kWriterPause);
      } while (!stop.load());
    });
  };
  std::thread cycle =
      writer([&] { diagnostics.setFault("plugin: ", "step failed"); }, fault_writes);
  std::thread sender =
      writer([&] { diagnostics.setRejection("command rejected: ", "pose_jump: too far"); },
             rejection_writes);
  // Read until both writers have overlapped the reader for a while.
  int torn_snapshots = 0;
  for (int i = 0; i < 5'000 || fault_writes.load() < 500 || rejection_writes.load() < 500; ++i) {
    const DiagnosticsSnapshot snapshot = diagnostics.snapshot();
    const bool fault_whole =
        snapshot.last_fault.empty() || snapshot.last_fault == "plugin: step failed";
    const bool rejection_whole = snapshot.last_rejection.empty() ||
                                 snapshot.last_rejection == "command rejected: pose_jump: too far";
    torn_snapshots += fault_whole && rejection_whole ? 0 : 1;
  }
  stop.store(true);
  cycle.join();
  sender.join();
  EXPECT_EQ(torn_snapshots, 0);
  const DiagnosticsSnapshot last = diagnostics.snapshot();
  EXPECT_EQ(last.last_fault, "plugin: step failed");
  EXPECT_EQ(last.last_rejection, "command rejected: pose_jump: too far");
  EXPECT_TRUE(last.last_error == last.last_fault || last.last_error == last.last_rejection);
}

}  // namespace
}  // namespace comply::pipeline
