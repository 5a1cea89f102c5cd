// Headless rendering: an EGL context without any surface (MuJoCo draws into its own offscreen
// framebuffer object), so no display, window or pbuffer is needed. Mesa's surfaceless platform is
// preferred because the default EGL display would try X11 or Wayland when DISPLAY happens to be
// set, and fail on machines where that display is unreachable.

#include "comply/sim/renderer.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "comply/sim/sim_error.hpp"
#include "gl_driver.hpp"

namespace comply::sim {
namespace {

const char* eglErrorName(EGLint code) {
  switch (code) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return "unknown EGL error";
  }
}

/// "<step> failed (EGL error 0x3009 EGL_BAD_MATCH)", with the error of the last EGL call.
std::string eglFailure(const std::string& step) {
  const EGLint code = eglGetError();
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(code));
  return "Renderer: " + step + " failed (EGL error " + hex + " " + eglErrorName(code) + ")";
}

bool hasExtension(const char* list, std::string_view name) {
  if (list == nullptr) {
    return false;
  }
  const std::string_view extensions(list);
  for (std::size_t at = extensions.find(name); at != std::string_view::npos;
       at = extensions.find(name, at + 1)) {
    const std::size_t end = at + name.size();
    if ((at == 0 || extensions[at - 1] == ' ') &&
        (end == extensions.size() || extensions[end] == ' ')) {
      return true;
    }
  }
  return false;
}

EGLDisplay surfacelessDisplay() {
  // Client extensions are queried on EGL_NO_DISPLAY; an EGL 1.4 library returns null (and sets
  // an error, cleared here so that it does not show up in a later message).
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  eglGetError();
  if (!hasExtension(client_extensions, "EGL_EXT_platform_base") ||
      !hasExtension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    return EGL_NO_DISPLAY;
  }
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) {
    return EGL_NO_DISPLAY;
  }
  return get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
}

bool initialize(EGLDisplay display) {
  EGLint major = 0;
  EGLint minor = 0;
  return display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) == EGL_TRUE;
}

EGLDisplay openDisplay() {
  if (EGLDisplay display = surfacelessDisplay(); initialize(display)) {
    return display;
  }
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY) {
    throw SimError(eglFailure(
        "Mesa's surfaceless platform is unavailable and eglGetDisplay(EGL_DEFAULT_DISPLAY)"));
  }
  if (!initialize(display)) {
    throw SimError(eglFailure("eglInitialize (default display)"));
  }
  return display;
}

/// One EGL display for the process, initialised by the first Renderer and terminated with the
/// last one: eglInitialize/eglTerminate are not reference counted by EGL itself, so terminating
/// per Renderer would pull the display from under the others.
class SharedDisplay {
 public:
  static EGLDisplay acquire() {
    const std::lock_guard lock(mutex_);
    if (users_ == 0) {
      display_ = openDisplay();
      keepGlDriverLoaded();
    }
    ++users_;
    return display_;
  }

  static void release() {
    const std::lock_guard lock(mutex_);
    if (--users_ == 0) {
      eglTerminate(display_);
      display_ = EGL_NO_DISPLAY;
    }
  }

 private:
  static inline std::mutex mutex_;
  static inline EGLDisplay display_ = EGL_NO_DISPLAY;
  static inline int users_ = 0;
};

EGLConfig chooseConfig(EGLDisplay display) {
  // The config only matters for the (unused) default framebuffer; MuJoCo allocates its own
  // colour and depth buffers. Pbuffer-capable configs are the ones Mesa offers surfaceless.
  const EGLint attributes[] = {EGL_RED_SIZE,
                               8,
                               EGL_GREEN_SIZE,
                               8,
                               EGL_BLUE_SIZE,
                               8,
                               EGL_DEPTH_SIZE,
                               24,
                               EGL_SURFACE_TYPE,
                               EGL_PBUFFER_BIT,
                               EGL_RENDERABLE_TYPE,
                               EGL_OPENGL_BIT,
                               EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display, attributes, &config, 1, &count) != EGL_TRUE) {
    throw SimError(eglFailure("eglChooseConfig"));
  }
  if (count < 1) {
    throw SimError(
        "Renderer: eglChooseConfig found no config with 8-bit RGB, 24-bit depth and desktop "
        "OpenGL");
  }
  return config;
}

void checkBufferSize(const mjModel& model, int width, int height) {
  if (width <= 0 || height <= 0) {
    throw SimError("Renderer: image size " + std::to_string(width) + " x " +
                   std::to_string(height) + " is not positive");
  }
  const int offwidth = model.vis.global.offwidth;
  const int offheight = model.vis.global.offheight;
  if (width > offwidth || height > offheight) {
    throw SimError("Renderer: image size " + std::to_string(width) + " x " +
                   std::to_string(height) + " exceeds the model's offscreen buffer " +
                   std::to_string(offwidth) + " x " + std::to_string(offheight) +
                   "; raise <visual><global offwidth=\"...\" offheight=\"...\"/></visual> in "
                   "the MJCF");
  }
}

}  // namespace

struct Renderer::Context {
  const mjModel* model;
  int width;
  int height;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext egl_context = EGL_NO_CONTEXT;
  bool gl_resources = false;  ///< mjr_makeContext succeeded: GL objects to free
  mjvScene scene;
  mjrContext render_context;
  mjvOption option;
  std::vector<unsigned char> bottom_up;  ///< glReadPixels rows, bottom row first

  Context(const mjModel& m, int w, int h) : model(&m), width(w), height(h) {
    mjv_defaultScene(&scene);
    mjr_defaultContext(&render_context);
    mjv_defaultOption(&option);
  }

  ~Context() {
    if (egl_context != EGL_NO_CONTEXT) {
      // MuJoCo deletes its GL objects in whatever context is current: it must be ours.
      if (gl_resources && eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_context)) {
        mjr_freeContext(&render_context);
      }
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, egl_context);
    }
    mjv_freeScene(&scene);
    if (display != EGL_NO_DISPLAY) {
      SharedDisplay::release();
    }
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  void makeCurrent() const {
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_context) != EGL_TRUE) {
      throw SimError(eglFailure("eglMakeCurrent (surfaceless)"));
    }
  }

  // Leaving no context current after each use lets another Renderer, a GLFW window (GLX) or
  // another thread take over: libglvnd refuses to switch between EGL and GLX while one of them
  // still has a context current on the thread.
  void releaseCurrent() const {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }

  void createEglContext() {
    display = SharedDisplay::acquire();
    const EGLConfig config = chooseConfig(display);
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
      throw SimError(eglFailure("eglBindAPI(EGL_OPENGL_API)"));
    }
    // Default attributes: a compatibility-profile context, which MuJoCo's fixed-function
    // renderer needs.
    egl_context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    if (egl_context == EGL_NO_CONTEXT) {
      throw SimError(eglFailure("eglCreateContext"));
    }
    makeCurrent();
  }

  void createMujocoContext() {
    // mjr_makeContext aborts the process (mju_error) without usable GL; fail politely first.
    const auto* version = glGetString(GL_VERSION);
    if (version == nullptr) {
      throw SimError("Renderer: the EGL context has no usable OpenGL (glGetString failed)");
    }
    mjv_makeScene(model, &scene, 2000);
    mjr_makeContext(model, &render_context, mjFONTSCALE_100);
    gl_resources = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &render_context);
    if (render_context.currentBuffer != mjFB_OFFSCREEN) {
      throw SimError("Renderer: MuJoCo could not set up its offscreen framebuffer on " +
                     std::string(reinterpret_cast<const char*>(version)));
    }
    // Rows of width * 3 bytes need not be 4-byte aligned and the GL default pads them to 4.
    // MuJoCo 2.2 happens to set this in mjr_readPixels too; not relying on that is cheap.
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    bottom_up.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  }
};

Renderer::Renderer(const mjModel& model, int width, int height) {
  checkBufferSize(model, width, height);
  context_ = std::make_unique<Context>(model, width, height);
  context_->createEglContext();
  context_->createMujocoContext();
  context_->releaseCurrent();
}

Renderer::~Renderer() = default;

namespace {

mjvCamera freeCamera(const CameraView& view) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) {
    camera.lookat[i] = view.lookat[i];
  }
  camera.distance = view.distance_m;
  camera.azimuth = view.azimuth_deg;
  camera.elevation = view.elevation_deg;
  return camera;
}

/// Puts both eyes of the scene's camera at `pose` (mono rendering averages them) with its field
/// of view: MuJoCo 2.2 cannot place a free camera by pose, and a wrist camera needs one.
void placeCamera(const mjModel& model, const CameraPose& pose, mjvScene& scene) {
  const double near_m = model.vis.map.znear * model.stat.extent;
  const double half_height = near_m * std::tan(pose.fovy_deg * mjPI / 360.0);
  for (mjvGLCamera& eye : scene.camera) {
    for (int i = 0; i < 3; ++i) {
      eye.pos[i] = static_cast<float>(pose.position[i]);
      eye.forward[i] = static_cast<float>(pose.forward[i]);
      eye.up[i] = static_cast<float>(pose.up[i]);
    }
    eye.frustum_center = 0.0F;
    eye.frustum_near = static_cast<float>(near_m);
    eye.frustum_far = static_cast<float>(model.vis.map.zfar * model.stat.extent);
    eye.frustum_bottom = static_cast<float>(-half_height);
    eye.frustum_top = static_cast<float>(half_height);
  }
}

}  // namespace

void Renderer::draw(const mjData& data, const CameraView& view, const CameraPose* pose,
                    Image& image) {
  Context& c = *context_;
  c.makeCurrent();

  mjvCamera camera = freeCamera(view);
  // mjv_updateScene takes mjData* only for scratch space on its stack, which it restores; the
  // state it reads is left as it was, so the caller's (non-const) mjData is not changed.
  mjv_updateScene(c.model, const_cast<mjData*>(&data), &c.option, nullptr, &camera, mjCAT_ALL,
                  &c.scene);
  if (pose != nullptr) {
    placeCamera(*c.model, *pose, c.scene);
  }
  const mjrRect viewport{0, 0, c.width, c.height};
  mjr_setBuffer(mjFB_OFFSCREEN, &c.render_context);
  mjr_render(viewport, &c.scene, &c.render_context);
  mjr_readPixels(c.bottom_up.data(), nullptr, viewport, &c.render_context);
  const int gl_error = mjr_getError();
  c.releaseCurrent();
  if (gl_error != 0) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(gl_error));
    throw SimError(std::string("Renderer: OpenGL error ") + hex + " while rendering");
  }

  image.width = c.width;
  image.height = c.height;
  image.rgb.resize(c.bottom_up.size());
  const std::size_t row_bytes = static_cast<std::size_t>(c.width) * 3;
  for (std::size_t y = 0; y < static_cast<std::size_t>(c.height); ++y) {
    const std::size_t source_row = static_cast<std::size_t>(c.height) - 1 - y;
    std::memcpy(image.rgb.data() + y * row_bytes, c.bottom_up.data() + source_row * row_bytes,
                row_bytes);
  }
}

Image Renderer::render(const mjData& data, const CameraView& view) {
  Image image;
  draw(data, view, nullptr, image);
  return image;
}

Image Renderer::render(const mjData& data, const CameraPose& pose) {
  Image image;
  draw(data, CameraView{}, &pose, image);
  return image;
}

void Renderer::render(const mjData& data, const CameraView& view, Image& image) {
  draw(data, view, nullptr, image);
}

void Renderer::render(const mjData& data, const CameraPose& pose, Image& image) {
  draw(data, CameraView{}, &pose, image);
}

int Renderer::width() const noexcept {
  return context_->width;
}
int Renderer::height() const noexcept {
  return context_->height;
}

}  // namespace comply::sim
