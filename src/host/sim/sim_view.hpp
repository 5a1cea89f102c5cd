#pragma once
// `comply sim --foxglove`: the live view of a simulated run.

#include <iosfwd>
#include <memory>

#include "comply/host/live_view.hpp"
#include "comply/host/sim_session.hpp"
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
SimView openView(
    const SimRunOptions& options,
    const std::shared_ptr<const pipeline::ResolvedController>& resolved,
    sim::SimulatedClock& clock);

}  // namespace comply::host
