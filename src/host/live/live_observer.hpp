#pragma once
// The control thread's side of `comply run`: after every cycle it records the timing (overruns,
// histograms of compute time and of cycle-start lateness as the loop measures it: against the
// wall clock, a paced simulation's too), notices when
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
#include "comply/host/diagnostics_message.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

/// p-quantile [s] of a histogram of LoopCounters (bin upper edge); 0 when empty.
double histogramQuantile(const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins,
                         double p);

template <typename Command>
class LiveObserver final : public hardware::LoopObserver {
 public:
  LiveObserver(pipeline::Wrapper<Command>& wrapper, pipeline::CommandGate& gate);

  void beforeCycle(std::uint64_t index, double time_s) override;
  void afterCycle(const hardware::CycleRecord& record) override;

  /// Before the loop runs: every cycle is recorded there (nullptr: none).
  void setRecording(HostRecording* recording) noexcept { recording_ = recording; }
  /// Any thread: activate or deactivate before the next cycle.
  void requestLifecycle(transport::RequestType request) noexcept;
  /// Why the last activation failed ("" if it did not); any thread.
  [[nodiscard]] std::string activationError() const;
  /// The publisher thread: the newest state sample; false when none is new.
  bool takeState(StateSample& sample);
  [[nodiscard]] const LoopCounters& counters() const noexcept { return counters_; }

 private:
  void fillSample(const hardware::CycleRecord& record) noexcept;

  pipeline::Wrapper<Command>& wrapper_;
  LoopCounters counters_;
  pipeline::CommandGate& gate_;
  TripleBuffer<StateSample> state_;
  StateSample sample_;  // the control thread's scratch
  JointState last_state_;
  StateSampler<Command> sampler_;
  HostRecording* recording_ = nullptr;
  std::atomic<std::uint8_t> lifecycle_request_{0};
  pipeline::MessageSlot activation_error_;
};

extern template class LiveObserver<CartesianCommand>;
extern template class LiveObserver<JointCommand>;

}  // namespace comply::host
