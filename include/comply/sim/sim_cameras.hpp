#pragma once
// Cameras on a simulated robot's scene, rendered offscreen (Renderer) as a policy observes: fixed
// in the scene, or carried by the TCP (a wrist camera). A visuomotor policy's images, and what a
// recording keeps of them.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "comply/sim/image.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::sim {

enum class CameraMount {
  kScene,  ///< fixed in the world, aimed by CameraSpec::view
  kTcp,    ///< carried by the TCP at CameraSpec::tcp_from_camera
};

struct CameraSpec {
  std::string name;
  /// Both even: the video a dataset makes of the frames takes 4:2:0 chroma.
  int width_px = 128;
  int height_px = 96;
  double fovy_deg = 45.0;  ///< vertical field of view
  /// Off by default: on a CPU renderer (llvmpipe) shadows double a frame's cost, and the floor's
  /// reflection triples it (docs/simulation.md#cameras).
  bool shadows = false;
  bool reflections = false;
  CameraMount mount = CameraMount::kScene;
  CameraView view;  ///< kScene: where it looks from (the world is the robot's base frame)
  /// kTcp: the camera's pose in the TCP frame, in the optical convention (x right, y down, z the
  /// viewing direction). The default looks along the tool's approach axis (TCP z) from 10 cm
  /// behind the TCP and 7 cm to its side, as a camera clamped to a wrist flange does.
  Eigen::Isometry3d tcp_from_camera = defaultWristMount();

  [[nodiscard]] static Eigen::Isometry3d defaultWristMount();
};

/// A camera's pose in the world from a scene view (MuJoCo's free-camera angles) or from the TCP.
[[nodiscard]] CameraPose scenePose(const CameraView& view, double fovy_deg);
[[nodiscard]] CameraPose tcpPose(const Eigen::Isometry3d& world_from_tcp,
                                 const Eigen::Isometry3d& tcp_from_camera, double fovy_deg);

class SimCameras {
 public:
  /// Renderers for `specs` on `plant`'s scene, which must outlive this (or the next attach()'s).
  /// Raises the model's offscreen buffer to the largest camera. Throws SimError for a spec that is
  /// not usable: an empty or repeated name, a size not positive or odd, a field of view outside
  /// (0, 180).
  SimCameras(SimulatedRobot& plant, std::vector<CameraSpec> specs);
  /// Renders `plant` from now on, a rebuild of the same scene (a reset's new plant), keeping the
  /// GL contexts: making them costs hundreds of milliseconds. Throws SimError for another scene.
  void attach(SimulatedRobot& plant);
  ~SimCameras();
  SimCameras(const SimCameras&) = delete;
  SimCameras& operator=(const SimCameras&) = delete;

  /// Every camera's image of the plant's current state, in the specs' order.
  const std::vector<Image>& render();
  [[nodiscard]] const std::vector<CameraSpec>& specs() const noexcept { return specs_; }

 private:
  SimulatedRobot* plant_;
  std::vector<CameraSpec> specs_;
  std::vector<std::unique_ptr<Renderer>> renderers_;
  std::vector<CameraPose> poses_;  ///< each camera's, a TCP camera's as of its last frame
  std::vector<Image> images_;
};

/// Throws SimError saying what is wrong with `specs` (see SimCameras).
void checkCameraSpecs(const std::vector<CameraSpec>& specs);

}  // namespace comply::sim
