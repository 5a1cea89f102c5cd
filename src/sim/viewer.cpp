// The interactive window: GLFW for the window and input, MuJoCo for the drawing. Mouse handling
// follows MuJoCo's own sample viewer (drag distances relative to the window height).

#include "comply/sim/viewer.hpp"

#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "comply/sim/sim_error.hpp"

namespace comply::sim {
namespace {

/// The last message GLFW reported, for the SimError text (GLFW reports errors by callback only).
std::string& lastGlfwError() {
  static std::string message;
  return message;
}

void onGlfwError(int code, const char* description) {
  lastGlfwError() = "GLFW error " + std::to_string(code) + ": " + description;
}

bool displayVariableSet() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

/// glfwInit once per process: it connects to the display server, which is not cheap, and its
/// answer does not change while the process runs. GLFW is never terminated because windows may
/// be opened again later; the connection goes with the process.
bool glfwReady() {
  static const bool ready = [] {
    glfwSetErrorCallback(onGlfwError);
    return glfwInit() == GLFW_TRUE;
  }();
  return ready;
}

}  // namespace

struct Viewer::Window {
  const mjModel* model;
  GLFWwindow* window = nullptr;
  mjvCamera camera;
  mjvOption option;
  mjvScene scene;
  mjrContext render_context;
  bool gl_resources = false;
  bool left_down = false;
  bool right_down = false;
  double last_x = 0.0;
  double last_y = 0.0;

  explicit Window(const mjModel& m) : model(&m) {
    mjv_defaultCamera(&camera);
    mjv_defaultOption(&option);
    mjv_defaultScene(&scene);
    mjr_defaultContext(&render_context);
  }

  ~Window() {
    if (window != nullptr) {
      glfwMakeContextCurrent(window);
      if (gl_resources) {
        mjr_freeContext(&render_context);
      }
      glfwMakeContextCurrent(nullptr);
      glfwDestroyWindow(window);
    }
    mjv_freeScene(&scene);
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  static Window& of(GLFWwindow* window) {
    return *static_cast<Window*>(glfwGetWindowUserPointer(window));
  }

  static void onMouseButton(GLFWwindow* window, int, int, int) {
    Window& self = of(window);
    self.left_down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    self.right_down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    glfwGetCursorPos(window, &self.last_x, &self.last_y);
  }

  static void onCursor(GLFWwindow* window, double x, double y) {
    Window& self = of(window);
    const double dx = x - self.last_x;
    const double dy = y - self.last_y;
    self.last_x = x;
    self.last_y = y;
    if (!self.left_down && !self.right_down) {
      return;
    }
    int width = 0;
    int height = 0;
    glfwGetWindowSize(window, &width, &height);
    if (height <= 0) {
      return;
    }
    // Shift switches from the vertical to the horizontal plane, as in MuJoCo's simulate.
    const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                       glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    const int action = self.right_down ? (shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V)
                                       : (shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V);
    mjv_moveCamera(self.model, action, dx / height, dy / height, &self.scene, &self.camera);
  }

  static void onScroll(GLFWwindow* window, double, double y_offset) {
    Window& self = of(window);
    mjv_moveCamera(self.model, mjMOUSE_ZOOM, 0.0, -0.05 * y_offset, &self.scene, &self.camera);
  }
};

Viewer::Viewer(const mjModel& model, const char* title, const CameraView& initial_view) {
  if (!displayVariableSet()) {
    throw SimError(
        "Viewer: no display: --view needs an X11 or Wayland display (DISPLAY and "
        "WAYLAND_DISPLAY are not set); run without --view, snapshots and plots are written to "
        "--out");
  }
  if (!glfwReady()) {
    throw SimError("Viewer: no usable display: GLFW could not connect to it (" + lastGlfwError() +
                   "); run without --view, snapshots and plots are written to --out");
  }
  window_ = std::make_unique<Window>(model);
  Window& w = *window_;
  // MuJoCo's renderer uses fixed-function OpenGL: the default (compatibility) context is needed.
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_SAMPLES, 4);
  w.window = glfwCreateWindow(1200, 900, title, nullptr, nullptr);
  if (w.window == nullptr) {
    throw SimError("Viewer: cannot open a window with OpenGL on this display (" + lastGlfwError() +
                   ")");
  }
  glfwMakeContextCurrent(w.window);
  // The simulation paces the frames; waiting for vertical sync would slow it down instead.
  glfwSwapInterval(0);

  w.camera.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) {
    w.camera.lookat[i] = initial_view.lookat[i];
  }
  w.camera.distance = initial_view.distance_m;
  w.camera.azimuth = initial_view.azimuth_deg;
  w.camera.elevation = initial_view.elevation_deg;

  mjv_makeScene(&model, &w.scene, 2000);
  mjr_makeContext(&model, &w.render_context, mjFONTSCALE_100);
  w.gl_resources = true;

  glfwSetWindowUserPointer(w.window, &w);
  glfwSetMouseButtonCallback(w.window, Window::onMouseButton);
  glfwSetCursorPosCallback(w.window, Window::onCursor);
  glfwSetScrollCallback(w.window, Window::onScroll);
  // Leave no context current so that an offscreen Renderer (EGL) can take the thread over.
  glfwMakeContextCurrent(nullptr);
}

Viewer::~Viewer() = default;

bool Viewer::show(const mjData& data) {
  Window& w = *window_;
  glfwPollEvents();
  glfwMakeContextCurrent(w.window);

  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(w.window, &width, &height);
  // As in Renderer::render: mjv_updateScene only borrows the data's stack and restores it.
  mjv_updateScene(w.model, const_cast<mjData*>(&data), &w.option, nullptr, &w.camera, mjCAT_ALL,
                  &w.scene);
  mjr_setBuffer(mjFB_WINDOW, &w.render_context);
  mjr_render(mjrRect{0, 0, width, height}, &w.scene, &w.render_context);
  glfwSwapBuffers(w.window);

  glfwMakeContextCurrent(nullptr);
  return glfwWindowShouldClose(w.window) == GLFW_FALSE;
}

bool Viewer::displayAvailable() noexcept {
  return displayVariableSet() && glfwReady();
}

}  // namespace comply::sim
