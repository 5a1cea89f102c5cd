#pragma once
// Snapshots (PNG, offscreen) and the live view of a simulated run; both optional, both outside
// the control cycle.

#include <filesystem>
#include <memory>
#include <string>

#include "comply/host/sim_session.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/sim/viewer.hpp"

namespace comply::host {

class SimPictures {
 public:
  /// A renderer when `options` asks for snapshots (a failure to get one is a note, not an error)
  /// and a window with `options.view` (no display: throws SimError).
  SimPictures(const SimRunOptions& options, const sim::SimulatedRobot& robot, SimSummary& summary);
  ~SimPictures();

  /// Writes `<out_dir>/<name>.png` and lists it in the summary.
  void snapshot(const sim::SimulatedRobot& robot, const std::string& name);
  /// Draws the window at most at 60 Hz of simulated time; false once the user closed it.
  bool show(const sim::SimulatedRobot& robot, double t);

 private:
  const SimRunOptions& options_;
  SimSummary& summary_;
  std::unique_ptr<sim::Renderer> renderer_;
  std::unique_ptr<sim::Viewer> viewer_;
  double next_view_s_ = 0.0;
};

}  // namespace comply::host
