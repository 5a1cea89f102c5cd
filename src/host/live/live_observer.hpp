#pragma once
// The control thread's side of `comply run`: after every cycle it records the timing (overruns,
// histograms of compute time and of cycle-start lateness against the wall clock), notices when
// the cycle took new commands (the stamp of the command in force moved) and publishes a fixed-size
// state sample. Everything it shares is lock-free and preallocated (atomics, an SPSC queue, a
// triple buffer), so the cycle neither allocates nor waits for the DDS threads. Lifecycle
// requests (activate, deactivate) are carried out here, between cycles, as the wrapper requires.

#include <array>
#include <atomic>
#include <cstdint>
#include <string>

#include "comply/core/spsc_queue.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

/// The cycle that took the commands up to `stamp_s` (the newest stamp in force).
struct AppliedEvent {
  std::uint64_t cycle = 0;
  double stamp_s = 0.0;
  transport::Stamp wall;  ///< wall clock at the end of that cycle
};

/// One cycle as the state topic shows it; fixed size, so copying it never allocates.
struct StateSample {
  std::uint64_t cycle = 0;
  transport::Stamp wall;
  pipeline::WrapperState state = pipeline::WrapperState::kInactive;
  JointState joints;
  JointVector torque;
  Eigen::Vector3d tcp_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond tcp_orientation = Eigen::Quaterniond::Identity();
  Vector6d tcp_twist = Vector6d::Zero();
  Vector6d contact_wrench = Vector6d::Zero();
  double reference_stamp_s = 0.0;
  std::uint32_t reference_fields = 0;
  Eigen::Vector3d reference_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond reference_orientation = Eigen::Quaterniond::Identity();
  JointVector reference_joint_position;
};

/// Cycle timing, written by the control thread, read by anyone.
struct LoopCounters {
  static constexpr std::size_t kBins = 200;
  static constexpr double kBinSeconds = 10e-6;  ///< 10 us bins: 0..2 ms, the last one open
  std::atomic<std::uint64_t> cycles{0};
  std::atomic<std::uint64_t> overruns{0};
  std::atomic<std::uint64_t> applied_dropped{0};  ///< applied events the publisher did not take
  std::array<std::atomic<std::uint64_t>, kBins> compute{};
  std::array<std::atomic<std::uint64_t>, kBins> lateness{};
};

/// p-quantile [s] of a histogram of LoopCounters (bin upper edge); 0 when empty.
double histogramQuantile(const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins,
                         double p);

template <typename Command>
class LiveObserver final : public hardware::LoopObserver {
 public:
  /// `plant`: the simulated robot for the contact wrench, or nullptr. `wall_origin_s`: the
  /// CLOCK_MONOTONIC time [s] at which the loop's clock reads 0.
  LiveObserver(pipeline::Wrapper<Command>& wrapper, const sim::SimulatedRobot* plant,
               double wall_origin_s);

  void beforeCycle(std::uint64_t index, double time_s) override;
  void afterCycle(const hardware::CycleRecord& record) override;

  /// Any thread: activate or deactivate before the next cycle.
  void requestLifecycle(transport::RequestType request) noexcept;
  /// Why the last activation failed ("" if it did not); any thread.
  [[nodiscard]] std::string activationError() const;
  /// The publisher thread (the only consumer): the next applied event, false when none waits.
  bool takeApplied(AppliedEvent& event) noexcept;
  /// The publisher thread: the newest state sample; false when none is new.
  bool takeState(StateSample& sample);
  [[nodiscard]] const LoopCounters& counters() const noexcept { return counters_; }

 private:
  void fillSample(const hardware::CycleRecord& record) noexcept;

  pipeline::Wrapper<Command>& wrapper_;
  const sim::SimulatedRobot* plant_;
  double wall_origin_s_;
  LoopCounters counters_;
  SpscQueue<AppliedEvent> applied_{4096};
  TripleBuffer<StateSample> state_;
  StateSample sample_;  // the control thread's scratch
  JointState last_state_;
  double last_stamp_s_ = -1.0;
  std::atomic<std::uint8_t> lifecycle_request_{0};
  pipeline::MessageSlot activation_error_;
};

extern template class LiveObserver<CartesianCommand>;
extern template class LiveObserver<JointCommand>;

}  // namespace comply::host
