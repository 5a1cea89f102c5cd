// The control thread's bookkeeping for `comply run` (see live_observer.hpp).

#include "live_observer.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <string>

#include "comply/core/clock.hpp"
#include "comply/pipeline/command_bus_variant.hpp"

namespace comply::host {

double histogramQuantile(const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins,
                         double p) {
  std::uint64_t total = 0;
  for (const auto& bin : bins) {
    total += bin.load(std::memory_order_relaxed);
  }
  if (total == 0) {
    return 0.0;
  }
  const double wanted = p * static_cast<double>(total);
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    seen += bins[i].load(std::memory_order_relaxed);
    if (static_cast<double>(seen) >= wanted) {
      return static_cast<double>(i + 1) * LoopCounters::kBinSeconds;
    }
  }
  return static_cast<double>(bins.size()) * LoopCounters::kBinSeconds;
}

template <typename Command>
LiveObserver<Command>::LiveObserver(pipeline::Wrapper<Command>& wrapper,
                                    pipeline::CommandGate& gate)
    : wrapper_(wrapper), gate_(gate), sampler_(wrapper) {
  const int dof = wrapper.dof();
  sample_.joints = JointState::zero(dof);
  sample_.torque.setZero(dof);
  sample_.reference_joint_position.setZero(dof);
  last_state_ = JointState::zero(dof);
}

template <typename Command>
void LiveObserver<Command>::beforeCycle(std::uint64_t /*index*/, double /*time_s*/) {
  // Lifecycle transitions run between cycles on this thread; they are rare operator requests,
  // not part of the cycle's real-time budget. Each is carried out in order and its outcome
  // handed to the publisher's thread; a request waits while that hand-over is full.
  for (const LifecycleRequest* request = lifecycle_requests_.front(); request != nullptr;
       request = lifecycle_requests_.front()) {
    LifecycleResult result{.request = *request};
    if (request->request == transport::RequestType::kActivate) {
      try {
        wrapper_.activate(last_state_);
      } catch (const std::exception& error) {
        std::snprintf(result.refusal.data(), result.refusal.size(), "activation failed: %s",
                      error.what());
      }
    } else if (request->request == transport::RequestType::kDeactivate) {
      wrapper_.deactivate();
    }
    if (!lifecycle_results_.push(result)) {
      return;  // carried out; its outcome is lost only if 64 wait unsettled
    }
    lifecycle_requests_.pop();
  }
}

template <typename Command>
void LiveObserver<Command>::afterCycle(const hardware::CycleRecord& record) {
  // The loop's lateness, on the wall clock even for a paced simulation: what a recording keeps.
  LoopCounters::count(counters_.lateness, record.start_lateness_s);
  counters_.countCycle(record.compute_s, record.overrun);
  if (record.state != nullptr) {
    last_state_ = *record.state;
  }
  // The chunks' timing records first, so that the outcome the cycle settles carries its own.
  const pipeline::Controller& controller = wrapper_.controller();
  if (const auto events = controller.chunks().events(); !events.empty()) {
    const std::int64_t now_ns = wallClockNanoseconds();
    for (const pipeline::ChunkTiming& timing : events) {
      if (!gate_.noteChunk(record.index, timing, controller.time(), now_ns)) {
        counters_.chunk_timings_lost.fetch_add(1, std::memory_order_relaxed);
      }
    }
  }
  if (!gate_.noteCycle(record.index, controller.idInForce(), wallClockNanoseconds)) {
    counters_.applied_deferred.fetch_add(1, std::memory_order_relaxed);
  }
  fillSample(record);
}

template <typename Command>
void LiveObserver<Command>::fillSample(const hardware::CycleRecord& record) noexcept {
  sampler_.fill(record, last_state_, transport::Stamp::now(), sample_);
  state_.publishFromSoleWriter(sample_);
  if (recording_ == nullptr && view_ == nullptr) {
    return;
  }
  const auto& in_force = std::get<pipeline::BusOf<Command>>(wrapper_.controller().lawBus());
  if (recording_ != nullptr) {
    recording_->cycle<Command>(sample_, in_force, record.compute_s, record.start_lateness_s);
  }
  if (view_ != nullptr) {
    view_->cycle<Command>(sample_, in_force, record.compute_s, record.start_lateness_s);
  }
}

template <typename Command>
bool LiveObserver<Command>::requestLifecycle(transport::RequestType request, std::int64_t stamp_ns,
                                             const pipeline::SenderId& sender) noexcept {
  return lifecycle_requests_.push({request, stamp_ns, sender});
}

template <typename Command>
void LiveObserver<Command>::noteReset(std::uint64_t number, std::int64_t stamp_ns,
                                      const pipeline::SenderId& sender) {
  const std::lock_guard<std::mutex> lock(resets_mutex_);
  pending_resets_.push_back({number, stamp_ns, sender});
}

template <typename Command>
void LiveObserver<Command>::settleRequests(pipeline::CommandGate& gate) {
  for (const LifecycleResult* result = lifecycle_results_.front(); result != nullptr;
       result = lifecycle_results_.front()) {
    const std::string refusal(result->refusal.data());
    if (!refusal.empty()) {
      gate.noteRefusal(refusal);
    }
    gate.settleRequest(result->request.stamp_ns, result->request.sender,
                       pipeline::CommandReason::kNone, refusal);
    lifecycle_results_.pop();
  }
  pipeline::ResetResult reset;
  while (wrapper_.controller().takeResetResult(reset)) {
    PendingReset pending{};
    {
      const std::lock_guard<std::mutex> lock(resets_mutex_);
      const auto it = std::find_if(pending_resets_.begin(), pending_resets_.end(),
                                   [&](const PendingReset& p) { return p.number == reset.number; });
      if (it == pending_resets_.end()) {
        continue;  // a reset no request of this host's asked for
      }
      pending = *it;
      pending_resets_.erase(it);
    }
    std::string refusal;
    if (reset.end == pipeline::ResetResult::End::kStateUnusable) {
      refusal = "reset refused: the measured state is not usable, the fault stays";
    } else if (reset.end == pipeline::ResetResult::End::kRobotStopped) {
      refusal =
          "reset refused: the robot is still stopped (diagnostics' last_fault says why); "
          "clear the stop on the robot first, the fault stays";
    }
    if (!refusal.empty()) {
      gate.noteRefusal(refusal);
    }
    gate.settleRequest(pending.stamp_ns, pending.sender, pipeline::CommandReason::kNone, refusal);
  }
}

template <typename Command>
bool LiveObserver<Command>::takeState(StateSample& sample) {
  if (!state_.update()) {
    return false;
  }
  sample = state_.read();
  return true;
}

template class LiveObserver<CartesianCommand>;
template class LiveObserver<JointCommand>;

}  // namespace comply::host
