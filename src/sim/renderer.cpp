// Headless rendering: an EGL context without any surface (MuJoCo draws into its own offscreen
// framebuffer object), so no display, window or pbuffer is needed (egl_display.hpp).

#include "comply/sim/renderer.hpp"

#include <EGL/egl.h>
#include <GL/gl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "comply/sim/sim_error.hpp"
#include "egl_display.hpp"

namespace comply::sim {
namespace {

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

namespace {

/// What the GL context holds of a model (its meshes, textures, ...) counted: another compilation of
/// the same scene has the same.
struct SceneCounts {
  int geoms, bodies, meshes, mesh_vertices, textures, materials, height_fields, skins;

  static SceneCounts of(const mjModel& m) {
    return {m.ngeom, m.nbody, m.nmesh, m.nmeshvert, m.ntex, m.nmat, m.nhfield, m.nskin};
  }
  bool operator==(const SceneCounts&) const = default;
};

}  // namespace

struct Renderer::Context {
  const mjModel* model;
  SceneCounts counts;
  int width;
  int height;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext egl_context = EGL_NO_CONTEXT;
  bool gl_resources = false;  ///< mjr_makeContext succeeded: GL objects to free
  mjvScene scene;
  mjrContext render_context;
  mjvOption option;
  std::vector<unsigned char> bottom_up;  ///< glReadPixels rows, bottom row first

  Context(const mjModel& m, int w, int h)
      : model(&m), counts(SceneCounts::of(m)), width(w), height(h) {
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

void Renderer::setShadows(bool on) noexcept {
  context_->scene.flags[mjRND_SHADOW] = on ? 1 : 0;
}

void Renderer::setReflections(bool on) noexcept {
  context_->scene.flags[mjRND_REFLECTION] = on ? 1 : 0;
}

void Renderer::rebind(const mjModel& model) {
  // Counted, not read from the model this was made for: a reset has destroyed it by now.
  const SceneCounts counts = SceneCounts::of(model);
  const SceneCounts& made_for = context_->counts;
  if (counts != made_for) {
    throw SimError("Renderer: cannot render a model of another scene than it was made for (" +
                   std::to_string(counts.geoms) + " geoms, " + std::to_string(counts.meshes) +
                   " meshes, " + std::to_string(counts.textures) + " textures against " +
                   std::to_string(made_for.geoms) + ", " + std::to_string(made_for.meshes) + ", " +
                   std::to_string(made_for.textures) + ")");
  }
  checkBufferSize(model, context_->width, context_->height);
  context_->model = &model;
}

int Renderer::width() const noexcept {
  return context_->width;
}
int Renderer::height() const noexcept {
  return context_->height;
}

}  // namespace comply::sim
