#pragma once
// An interactive window on a running simulation (GLFW): left drag rotates, right drag pans, the
// wheel zooms. Only where a display exists; headless runs use Renderer.

#include <mujoco/mujoco.h>

#include <memory>

#include "comply/sim/renderer.hpp"

namespace comply::sim {

class Viewer {
 public:
  /// Opens a window titled `title` on `model`. Throws SimError with a clear message when there is
  /// no display (DISPLAY / WAYLAND_DISPLAY unset or unusable) or no OpenGL.
  Viewer(const mjModel& model, const char* title, const CameraView& initial_view);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// Draws `data` and handles window events. Returns false once the user closed the window.
  /// Does not wait for vertical sync (the caller paces frames) and leaves no GL context current.
  bool show(const mjData& data);

  /// True when a display is reachable (cheap check before constructing a Viewer).
  static bool displayAvailable() noexcept;

 private:
  struct Window;
  std::unique_ptr<Window> window_;
};

}  // namespace comply::sim
