// Cameras on a simulated robot's scene (see sim_cameras.hpp).

#include "comply/sim/sim_cameras.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "comply/sim/sim_error.hpp"

namespace comply::sim {
namespace {

void copy(const Eigen::Vector3d& from, double (&to)[3]) {
  for (int i = 0; i < 3; ++i) {
    to[i] = from[i];
  }
}

}  // namespace

Eigen::Isometry3d CameraSpec::defaultWristMount() {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.translation() = Eigen::Vector3d(0.0, 0.07, -0.10);
  return mount;
}

CameraPose scenePose(const CameraView& view, double fovy_deg) {
  // MuJoCo's free camera: azimuth about world z, elevation above the horizontal, at `distance`
  // back from the point it looks at.
  const double azimuth = view.azimuth_deg * M_PI / 180.0;
  const double elevation = view.elevation_deg * M_PI / 180.0;
  const Eigen::Vector3d forward(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  const Eigen::Vector3d up(-std::sin(elevation) * std::cos(azimuth),
                           -std::sin(elevation) * std::sin(azimuth), std::cos(elevation));
  const Eigen::Vector3d lookat(view.lookat[0], view.lookat[1], view.lookat[2]);
  CameraPose pose;
  copy(lookat - view.distance_m * forward, pose.position);
  copy(forward, pose.forward);
  copy(up, pose.up);
  pose.fovy_deg = fovy_deg;
  return pose;
}

CameraPose tcpPose(const Eigen::Isometry3d& world_from_tcp,
                   const Eigen::Isometry3d& tcp_from_camera, double fovy_deg) {
  const Eigen::Isometry3d world_from_camera = world_from_tcp * tcp_from_camera;
  const Eigen::Matrix3d axes = world_from_camera.linear();
  CameraPose pose;
  copy(world_from_camera.translation(), pose.position);
  copy(axes.col(2), pose.forward);  // optical z: the viewing direction
  copy(-axes.col(1), pose.up);      // optical y points down the image
  pose.fovy_deg = fovy_deg;
  return pose;
}

void checkCameraSpecs(const std::vector<CameraSpec>& specs) {
  std::set<std::string> names;
  for (const CameraSpec& spec : specs) {
    const std::string which = "camera '" + spec.name + "'";
    if (spec.name.empty()) {
      throw SimError("a camera needs a name");
    }
    if (!names.insert(spec.name).second) {
      throw SimError(which + " is named twice");
    }
    if (spec.width_px <= 0 || spec.height_px <= 0 || spec.width_px % 2 != 0 ||
        spec.height_px % 2 != 0) {
      throw SimError(which + ": " + std::to_string(spec.width_px) + " x " +
                     std::to_string(spec.height_px) +
                     " pixels; width and height must be positive and even (a dataset's video "
                     "takes 4:2:0 chroma)");
    }
    if (!(spec.fovy_deg > 0.0 && spec.fovy_deg < 180.0)) {
      throw SimError(which + ": fovy " + std::to_string(spec.fovy_deg) +
                     " deg is outside (0, 180)");
    }
    if (!spec.tcp_from_camera.matrix().allFinite()) {
      throw SimError(which + ": its mount on the TCP is not finite");
    }
  }
}

namespace {

/// The offscreen buffer of `plant`'s model raised to the largest camera.
mjModel& withBuffer(SimulatedRobot& plant, const std::vector<CameraSpec>& specs) {
  mjModel& model = plant.mutableMujocoModel();
  for (const CameraSpec& spec : specs) {
    model.vis.global.offwidth = std::max(model.vis.global.offwidth, spec.width_px);
    model.vis.global.offheight = std::max(model.vis.global.offheight, spec.height_px);
  }
  return model;
}

}  // namespace

SimCameras::SimCameras(SimulatedRobot& plant, std::vector<CameraSpec> specs)
    : plant_(&plant), specs_(std::move(specs)) {
  checkCameraSpecs(specs_);
  const mjModel& model = withBuffer(plant, specs_);
  for (const CameraSpec& spec : specs_) {
    renderers_.push_back(std::make_unique<Renderer>(model, spec.width_px, spec.height_px));
    renderers_.back()->setShadows(spec.shadows);
    renderers_.back()->setReflections(spec.reflections);
    // A scene camera never moves: its pose once, here.
    poses_.push_back(scenePose(spec.view, spec.fovy_deg));
  }
  images_.resize(specs_.size());
}

void SimCameras::attach(SimulatedRobot& plant) {
  const mjModel& model = withBuffer(plant, specs_);
  for (const std::unique_ptr<Renderer>& renderer : renderers_) {
    renderer->rebind(model);
  }
  plant_ = &plant;
}

SimCameras::~SimCameras() = default;

const std::vector<Image>& SimCameras::render() {
  const mjData& data = plant_->mujocoData();
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const CameraSpec& spec = specs_[i];
    if (spec.mount == CameraMount::kTcp) {
      poses_[i] = tcpPose(plant_->tcpPose(), spec.tcp_from_camera, spec.fovy_deg);
    }
    renderers_[i]->render(data, poses_[i], images_[i]);
  }
  return images_;
}

}  // namespace comply::sim
