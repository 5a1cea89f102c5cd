// The fault and rejection texts of the diagnostics, written by two threads (the cycle and the
// intake), never tear and never block a reader.

#include "comply/pipeline/diagnostics.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>

namespace comply::pipeline {
namespace {

TEST(Diagnostics, FaultAndRejectionWritersNeverBlockAReader) {
  // Two writers on one text used to leave its sequence counter odd and a reader spinning.
  Diagnostics diagnostics;
  std::atomic<bool> stop{false};
  std::thread cycle([&] {
    while (!stop.load()) {
      diagnostics.setFault("plugin: ", "step failed");
    }
  });
  std::thread sender([&] {
    while (!stop.load()) {
      diagnostics.setRejection("command rejected: ", "pose_jump: too far");
    }
  });
  for (int i = 0; i < 20'000; ++i) {
    const DiagnosticsSnapshot snapshot = diagnostics.snapshot();
    ASSERT_TRUE(snapshot.last_fault.empty() || snapshot.last_fault == "plugin: step failed");
    ASSERT_TRUE(snapshot.last_rejection.empty() ||
                snapshot.last_rejection == "command rejected: pose_jump: too far");
  }
  stop.store(true);
  cycle.join();
  sender.join();
  const DiagnosticsSnapshot last = diagnostics.snapshot();
  EXPECT_EQ(last.last_fault, "plugin: step failed");
  EXPECT_EQ(last.last_rejection, "command rejected: pose_jump: too far");
  EXPECT_TRUE(last.last_error == last.last_fault || last.last_error == last.last_rejection);
}

}  // namespace
}  // namespace comply::pipeline
