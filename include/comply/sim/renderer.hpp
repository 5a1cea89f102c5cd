#pragma once
// Offscreen rendering of a MuJoCo scene to an Image, headless: an EGL surfaceless context on
// whatever OpenGL the machine has (llvmpipe when there is no GPU). No display needed.

#include <mujoco/mujoco.h>

#include <memory>

#include "comply/sim/image.hpp"

namespace comply::sim {

/// A free camera looking at `lookat` [m, world frame] from `distance_m`, turned `azimuth_deg`
/// about the world z axis and raised `elevation_deg` (negative looks down).
struct CameraView {
  double lookat[3] = {0.3, 0.0, 0.4};
  double distance_m = 2.0;
  double azimuth_deg = 135.0;
  double elevation_deg = -20.0;
};

/// A camera at a pose in the world: at `position` [m], looking along `forward`, `up` the image's
/// up direction (both unit and orthogonal), `fovy_deg` the vertical field of view. What a camera
/// carried by a body (a wrist camera) gives each frame.
struct CameraPose {
  double position[3] = {0.0, 0.0, 0.0};
  double forward[3] = {1.0, 0.0, 0.0};
  double up[3] = {0.0, 0.0, 1.0};
  double fovy_deg = 45.0;
};

class Renderer {
 public:
  /// Creates the GL context and MuJoCo's render context for `model`, which must outlive the
  /// Renderer. The model's offscreen buffer (visual/global offwidth, offheight) must be at least
  /// width x height. Throws SimError saying what is missing (no EGL display, no GL context,
  /// buffer too small).
  Renderer(const mjModel& model, int width, int height);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders the state in `data` (positions must be current: after mj_forward or mj_step).
  /// Makes this Renderer's GL context current on the calling thread and releases it before
  /// returning, so several Renderers (and a Viewer) can take turns; one call at a time per
  /// Renderer. Throws SimError when the context cannot be made current or GL reports an error.
  [[nodiscard]] Image render(const mjData& data, const CameraView& view);
  /// The same from a camera at `pose`.
  [[nodiscard]] Image render(const mjData& data, const CameraPose& pose);
  /// The same into `image` (resized once; no allocation after the first frame of a size).
  void render(const mjData& data, const CameraView& view, Image& image);
  void render(const mjData& data, const CameraPose& pose, Image& image);

  /// Shadows on (the default) or off: on a CPU renderer (llvmpipe) a frame with them costs about
  /// twice one without, the lights' shadow maps drawn each frame.
  void setShadows(bool on) noexcept;
  /// Reflections in reflective surfaces (the floor) on (the default) or off: with them the scene
  /// is drawn twice per frame, and on a CPU renderer a frame costs about three times as much.
  void setReflections(bool on) noexcept;
  /// Renders `model` from now on: another compilation of the scene this Renderer was made for
  /// (a simulation reset rebuilds its plant), whose meshes and textures the GL context already
  /// holds, so that a reset does not pay for a new context. Throws SimError, changing nothing,
  /// when `model` is not of the same scene (other counts of meshes, textures, geoms, bodies).
  void rebind(const mjModel& model);

  [[nodiscard]] int width() const noexcept;
  [[nodiscard]] int height() const noexcept;

 private:
  struct Context;
  /// Renders from `view`, or from `pose` when not null.
  void draw(const mjData& data, const CameraView& view, const CameraPose* pose, Image& image);
  std::unique_ptr<Context> context_;
};

}  // namespace comply::sim
