#pragma once
// The process's EGL display for headless rendering, its config, and EGL's errors in words.
// Private to sim_render (renderer.cpp).

#include <EGL/egl.h>

#include <string>

namespace comply::sim {

/// "Renderer: <step> failed (EGL error 0x3009 EGL_BAD_MATCH)", with the error of the last EGL
/// call.
std::string eglFailure(const std::string& step);

/// One EGL display for the process, initialised by the first Renderer and terminated with the
/// last one: eglInitialize/eglTerminate are not reference counted by EGL itself, so terminating
/// per Renderer would pull the display from under the others. Mesa's surfaceless platform when
/// there is one, else the default display. acquire() throws SimError when neither initialises.
class SharedDisplay {
 public:
  static EGLDisplay acquire();
  static void release();
};

/// A config with 8-bit RGB, 24-bit depth and desktop OpenGL. Throws SimError.
EGLConfig chooseConfig(EGLDisplay display);

}  // namespace comply::sim
