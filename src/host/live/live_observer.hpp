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
#include <deque>
#include <mutex>
#include <string>

#include "comply/core/spsc_queue.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/diagnostics_message.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/live_view.hpp"
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
  /// Before the loop runs: every cycle is shown there while a viewer watches (nullptr: none).
  void setView(LiveView* view) noexcept { view_ = view; }
  /// The intake's thread: activate or deactivate before the next cycle; the request (`stamp_ns`,
  /// `sender`) is settled when it was carried out or failed (settleRequests()). False when too
  /// many wait (the caller refuses it).
  bool requestLifecycle(transport::RequestType request, std::int64_t stamp_ns,
                        const pipeline::SenderId& sender) noexcept;
  /// The intake's thread: the reset numbered `number` (Wrapper::reset()) from `sender` is
  /// settled when the cycle has decided it.
  void noteReset(std::uint64_t number, std::int64_t stamp_ns, const pipeline::SenderId& sender);
  /// The publisher's thread: settles the lifecycle requests the control thread carried out or
  /// failed, and the resets the cycle decided, with `gate`.
  void settleRequests(pipeline::CommandGate& gate);
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
  LiveView* view_ = nullptr;
  struct LifecycleRequest {
    transport::RequestType request = transport::RequestType::kProbe;
    std::int64_t stamp_ns = 0;
    pipeline::SenderId sender{};
  };
  struct LifecycleResult {
    LifecycleRequest request;
    std::array<char, 240> refusal{};  // empty: carried out
  };
  struct PendingReset {
    std::uint64_t number;
    std::int64_t stamp_ns;
    pipeline::SenderId sender;
  };
  SpscQueue<LifecycleRequest> lifecycle_requests_{32};  // intake -> control thread
  SpscQueue<LifecycleResult> lifecycle_results_{64};    // control -> publisher thread
  std::mutex resets_mutex_;                             // intake and publisher threads only
  std::deque<PendingReset> pending_resets_;
};

extern template class LiveObserver<CartesianCommand>;
extern template class LiveObserver<JointCommand>;

}  // namespace comply::host
