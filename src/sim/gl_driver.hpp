#pragma once
// The OpenGL driver EGL loads behind the display, kept for the life of the process.

namespace comply::sim {

/// Keeps every Mesa driver library now loaded (a `*_dri.so` or `libgallium*`) mapped until the
/// process exits, even after eglTerminate. Call after eglInitialize. Idempotent; never throws.
void keepGlDriverLoaded() noexcept;

}  // namespace comply::sim
