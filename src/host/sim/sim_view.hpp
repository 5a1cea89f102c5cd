#pragma once
// `comply sim --foxglove`: the live view of a simulated run.

#include <iosfwd>
#include <memory>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/live_view.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"

namespace comply::host {

/// Says what the view sent and dropped on the run's progress stream when it closes.
struct ViewCloser {
  std::ostream* progress = nullptr;
  void operator()(LiveView* view) const;
};
using SimView = std::unique_ptr<LiveView, ViewCloser>;

/// The live view of SimRunOptions::foxglove (none without it): the clock paces while a viewer
/// watches, and the run waits for the first one as long as foxglove_wait_s says.
SimView openView(const SimRunOptions& options,
                 const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                 sim::SimulatedClock& clock);

/// The view's diagnostics at simulated time `time_s` (a simulation has no transport nor gate:
/// their counts stay 0).
void viewDiagnostics(LiveView& view, const pipeline::DiagnosticsSnapshot& diagnostics,
                     double period_s, double time_s);

/// A simulated cycle (`sample` filled) to the recording and the view, either of them null; the
/// view also gets the diagnostics every 100 cycles.
template <typename Command>
void forwardCycle(HostRecording* recording, LiveView* view, const StateSample& sample,
                  const pipeline::Wrapper<Command>& wrapper, const hardware::CycleRecord& record) {
  const auto& in_force = std::get<pipeline::BusOf<Command>>(wrapper.controller().lawBus());
  if (recording != nullptr) {
    recording->cycle<Command>(sample, in_force, record.controller_s, record.start_lateness_s);
  }
  if (view != nullptr) {
    view->cycle<Command>(sample, in_force, record.controller_s, record.start_lateness_s);
    if (record.index % 100 == 0 && view->viewing()) {
      viewDiagnostics(*view, wrapper.diagnostics(), record.period_s, record.time_s);
    }
  }
}

}  // namespace comply::host
