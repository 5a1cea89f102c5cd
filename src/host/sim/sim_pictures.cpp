#include "sim_pictures.hpp"

#include "comply/sim/image.hpp"
#include "comply/sim/sim_error.hpp"

namespace comply::host {
namespace {

constexpr double kViewerPeriodS = 1.0 / 60.0;

}  // namespace

SimPictures::SimPictures(const SimRunOptions& options, const sim::SimulatedRobot& robot,
                         SimSummary& summary)
    : options_(options), summary_(summary) {
  if (options.snapshots && !options.out_dir.empty()) {
    try {
      renderer_ = std::make_unique<sim::Renderer>(robot.mujocoModel(), options.image_width,
                                                  options.image_height);
    } catch (const sim::SimError& error) {
      addMessage(summary, std::string("snapshots skipped: ") + error.what(), options.progress);
    }
  }
  if (options.view) {
    viewer_ = std::make_unique<sim::Viewer>(robot.mujocoModel(), "comply sim", options.task.camera);
  }
}

SimPictures::~SimPictures() = default;

void SimPictures::snapshot(const sim::SimulatedRobot& robot, const std::string& name) {
  if (!renderer_) {
    return;
  }
  const std::filesystem::path file = options_.out_dir / (name + ".png");
  sim::writePng(renderer_->render(robot.mujocoData(), options_.task.camera), file);
  summary_.files.push_back(file);
}

bool SimPictures::show(const sim::SimulatedRobot& robot, double t) {
  if (!viewer_ || t < next_view_s_) {
    return true;
  }
  next_view_s_ = t + kViewerPeriodS;
  return viewer_->show(robot.mujocoData());
}

}  // namespace comply::host
