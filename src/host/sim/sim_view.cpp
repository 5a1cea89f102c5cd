// `comply sim --foxglove` (see sim_view.hpp).

#include "sim_view.hpp"

#include <ostream>

#include "comply/host/diagnostics_message.hpp"

namespace comply::host {

void ViewCloser::operator()(LiveView* view) const {
  if (progress != nullptr) {
    *progress << "comply sim: " << describeViewStats(view->stats()) << std::endl;
  }
  delete view;
}

SimView openView(const SimRunOptions& options,
                 const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                 sim::SimulatedClock& clock) {
  if (!options.foxglove) {
    return SimView(nullptr, ViewCloser{});
  }
  SimView view(new LiveView(*options.foxglove, resolved, "comply"), ViewCloser{options.progress});
  clock.paceWhile(&view->viewingFlag());
  if (options.progress != nullptr) {
    *options.progress << "comply sim: Foxglove live view on " << view->url()
                      << " (real time while a viewer is connected)" << std::endl;
  }
  if (options.foxglove_wait_s > 0.0 && !view->waitForViewer(options.foxglove_wait_s) &&
      options.progress != nullptr) {
    *options.progress << "comply sim: no viewer came in " << options.foxglove_wait_s
                      << " s; running without one" << std::endl;
  }
  return view;
}

void viewDiagnostics(LiveView& view, const pipeline::DiagnosticsSnapshot& diagnostics,
                     double period_s, double time_s) {
  transport::DiagnosticsMessage message =
      diagnosticsMessage(diagnostics, LoopCounters{}, period_s, {}, 0, "comply", {});
  message.header.stamp = transport::Stamp::fromSeconds(time_s);
  view.diagnostics(message);
}

}  // namespace comply::host
