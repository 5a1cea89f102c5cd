// The EGL display for headless rendering (see egl_display.hpp). Mesa's surfaceless platform is
// preferred because the default EGL display would try X11 or Wayland when DISPLAY happens to be
// set, and fail on machines where that display is unreachable.

#include "egl_display.hpp"

#include <EGL/eglext.h>

#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>

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

std::mutex display_mutex;
EGLDisplay display = EGL_NO_DISPLAY;
int display_users = 0;

}  // namespace

/// "<step> failed (EGL error 0x3009 EGL_BAD_MATCH)", with the error of the last EGL call.
std::string eglFailure(const std::string& step) {
  const EGLint code = eglGetError();
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(code));
  return "Renderer: " + step + " failed (EGL error " + hex + " " + eglErrorName(code) + ")";
}

EGLDisplay SharedDisplay::acquire() {
  const std::lock_guard lock(display_mutex);
  if (display_users == 0) {
    display = openDisplay();
    keepGlDriverLoaded();
  }
  ++display_users;
  return display;
}

void SharedDisplay::release() {
  const std::lock_guard lock(display_mutex);
  if (--display_users == 0) {
    eglTerminate(display);
    display = EGL_NO_DISPLAY;
  }
}

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

}  // namespace comply::sim
